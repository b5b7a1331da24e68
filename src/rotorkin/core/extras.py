"""Optional libraries of the extras, imported on first use with one line naming the install.

The core install (``pip install rotorkin``) computes and writes everything without
them; a function that returns one of their objects (an :class:`xarray.Dataset`)
imports it here. When it is missing, the ``ModuleNotFoundError`` raised names the
extra and its pip command (the command line turns it into its one-line error).
"""

from __future__ import annotations

__all__ = ["xarray_module"]


def xarray_module(what: str = "this function"):
    """:mod:`xarray` (the ``xarray`` extra), or one line naming ``pip install "rotorkin[xarray]"``.

    Parameters
    ----------
    what : str
        What needs it, for the message (e.g. ``"rotorkin.sweep.execute"``).

    Raises
    ------
    ModuleNotFoundError
        With ``name`` the missing module (``xarray`` or ``pandas``).
    """
    try:
        import xarray
    except ImportError as exc:
        name = (getattr(exc, "name", None) or "xarray").split(".")[0]
        if name not in ("xarray", "pandas"):
            name = "xarray"
        raise ModuleNotFoundError(
            f"{what} needs the xarray extra: pip install "
            f'"rotorkin[xarray]" ({name} is not installed)',
            name=name,
        ) from None
    return xarray
