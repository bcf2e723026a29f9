"""rockdesign: design checks for rocking and rolling-and-rocking structures (see README)."""
__version__ = "0.1.0"
