"""RoundingError, and the compiled engine it comes from.

The engine's own exception class is the public one, so `except MeshRound.RoundingError` catches errors
raised in C++ and in Python alike.  Each has `.code`, one of CODES (README, "Errors").  If the compiled module is missing (not built yet), `import MeshRound`
still works, the workbench still loads, and every call raises a RoundingError that says how to build it.
"""
import threading

try:
    from . import _meshround_core as core
    RoundingError = core.RoundingError
    CancelToken = core.CancelToken
    CORE_IMPORT_ERROR = None
except ImportError as exc:  # not built, or built for another Python
    core = None
    CORE_IMPORT_ERROR = exc

    class CancelToken:
        """Stand-in for the engine's CancelToken (no engine: every call fails anyway)."""

        def __init__(self):
            self._event = threading.Event()

        def cancel(self):
            self._event.set()

        @property
        def is_cancelled(self):
            return self._event.is_set()

    class RoundingError(ValueError):
        """A rounding could not be made; the message names the cause, .code the kind (as the engine's)."""

        def __init__(self, message, code="invalid_input"):
            super().__init__(message)
            self.code = code


CANCELLED_MESSAGE = "the rounding was cancelled"  # the engine's own (kCancelledMessage)


def check_cancelled(cancel):
    """Raise RoundingError(code "cancelled") if the CancelToken `cancel` (or None) was cancelled."""
    if cancel is None:
        return
    if not isinstance(cancel, CancelToken):
        raise RoundingError(f"cancel must be a MeshRound.CancelToken or None, not {type(cancel).__name__}")
    if cancel.is_cancelled:
        raise RoundingError(CANCELLED_MESSAGE, "cancelled")


# Every code a RoundingError can carry (the engine's ErrorCode, cpp_core/include/meshround/types.h).
CODES = ("invalid_input", "no_sharp_edge", "non_manifold_input", "radius_too_large", "radius_too_small",
         "beyond_reach", "corner_not_blendable", "surface_failed", "result_invalid", "cancelled", "work_limit",
         "not_a_round")


def require_core():
    """The compiled engine module, or a RoundingError explaining why it cannot be used."""
    if core is None:
        raise RoundingError(
            "the compiled MeshRound engine (_meshround_core) could not be imported "
            f"({CORE_IMPORT_ERROR}); build it with `cmake -S <repo> -B <repo>/build && "
            "cmake --build <repo>/build`")
    return core
