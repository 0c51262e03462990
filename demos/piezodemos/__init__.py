"""What the demos and studies share: running the engines on a config and
comparing their outputs (runs, compare), and pictures of a run (figures)."""
