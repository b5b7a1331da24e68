"""Drives: one module per drive family, from the input-shaft angle to two members."""
