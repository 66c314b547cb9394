"""Small immutable records for modules on the planner's start-up path, without ``dataclasses``.

``import dataclasses`` loads ``inspect`` (and with it ``ast``, ``dis``, ``tokenize``,
``linecache``): about a fifth of a small planner run's whole process. A record
here behaves like a frozen dataclass for what the planner uses: fields are set
once in ``__init__`` (through ``_set_fields``), assigning one afterwards raises
``AttributeError``, and equality, hashing and ``repr`` go by the fields, in the
order of ``__slots__``.
"""

from __future__ import annotations


class FrozenRecord:
    """Base class: list the fields in ``__slots__`` and set them in ``__init__`` with ``_set_fields``.

    ``__init__`` takes the fields positionally in the order of ``__slots__``
    (pickling and copying rebuild a record that way).
    """

    __slots__ = ()

    def _set_fields(self, **values: object) -> None:
        for name, value in values.items():
            object.__setattr__(self, name, value)

    def _field_names(self) -> tuple[str, ...]:
        return self.__slots__

    def _field_values(self) -> tuple[object, ...]:
        return tuple(getattr(self, name) for name in self._field_names())

    def __setattr__(self, name: str, value: object) -> None:
        raise AttributeError(f"cannot assign to field {name!r} of a {type(self).__name__}")

    def __delattr__(self, name: str) -> None:
        raise AttributeError(f"cannot delete field {name!r} of a {type(self).__name__}")

    def __eq__(self, other: object) -> bool:
        if other.__class__ is not self.__class__:
            return NotImplemented
        assert isinstance(other, FrozenRecord)
        return self._field_values() == other._field_values()

    def __hash__(self) -> int:
        return hash(self._field_values())

    def __reduce__(self) -> tuple[type[FrozenRecord], tuple[object, ...]]:
        return self.__class__, self._field_values()

    def __repr__(self) -> str:
        fields = ", ".join(f"{name}={getattr(self, name)!r}" for name in self._field_names())
        return f"{type(self).__name__}({fields})"
