"""Command-line interface ``wheelrail``: one module per sub-command (see :mod:`.main`)."""
