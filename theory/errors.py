"""The one error type for invalid user input: it names the parameter and its valid range."""

from __future__ import annotations


class ParameterError(ValueError):
    """A parameter outside its valid range, missing, misspelled or not a number."""

    def __init__(self, name: str, value: object, valid: str, hint: str = "") -> None:
        self.name = name
        self.value = value
        self.valid = valid
        msg = f"{name} = {value!r} is invalid: {valid}"
        if hint:
            msg += f" ({hint})"
        super().__init__(msg)


class MissingDependency(RuntimeError):
    """A library lgw declares as a dependency is absent from this environment (a partial or
    old install): the message names the package and the command that installs it."""

    def __init__(self, package: str, needed_for: str) -> None:
        self.package = package
        super().__init__(f"the Python package {package!r} is missing; it is needed for "
                         f"{needed_for} (reinstall lgw, or: pip install {package})")


class NotApplicableError(ParameterError):
    """A verb asked of a system it cannot apply to; the message says why (exit 2)."""

    def __init__(self, verb: str, system: str, reason: str) -> None:
        ValueError.__init__(self, f"lgw {verb} {system} does not apply: {reason}")
        self.name, self.value, self.valid = f"lgw {verb} {system}", system, reason
