"""The error of a bad input, below every layer: each layer's own errors (a hole's, a unit's, a
scenario's) are InputErrors, so that ``except mcrun.InputError`` catches every input a user can
get wrong, and the command line prints each as one line with exit code 2."""


class InputError(ValueError):
    """An input out of its documented range; the message is one line meant for the user."""
