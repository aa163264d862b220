"""Description parsing and object recall (the paper's Joint Probability distance)."""
