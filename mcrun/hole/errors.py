"""The one error of the hole layer."""

from mcrun.errors import InputError


class HoleError(InputError):
    """A hole, its map or its ground cannot be used; the message is one line naming the file,
    the key or feature, and what is allowed."""
