"""Input and output at the edges: config files and units in, data files out."""
