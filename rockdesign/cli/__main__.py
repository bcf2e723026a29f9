"""``python -m rockdesign.cli``: the same as the ``rockdesign`` command."""
from .app import main

main()
