"""The tools' bad-input error (exit status 2), on its own so that every module can raise it
without importing the figure machinery (common.py imports runinfo.py, which raises it)."""


class InputError(Exception):
    """Bad input: the message is complete and meant for the user (exit status 2)."""
