"""Report: figures and reports built on the studies."""
