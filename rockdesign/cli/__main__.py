"""``python -m rockdesign.cli``: the same as the ``rockdesign`` command."""
from .app import main

if __name__ == "__main__":   # importing the module (e.g. walking the package) runs nothing
    main()
