"""Reading a domain's binding (``<domain>.binding.toml`` beside the domain file) into a
``DomainBinding``, checked against the domain: every action bound to a known skill with each
required role played by one of its parameters, every predicate given a relation of its arity,
every type one the domain declares. Each mistake is a ``BindingFileError`` naming the file and
the key.

The file lies beside the domain file the path resolves to, so a domain reached through a
symbolic link (``pddl/domain.pddl``) finds its binding; a copied domain needs its binding copied.
"""

from __future__ import annotations

import tomllib
from pathlib import Path
from types import MappingProxyType
from typing import Any, Final

from kitchen_tamp.kitchen.binding import RELATIONS, SKILL_ROLES, ActionBinding, DomainBinding
from kitchen_tamp.kitchen.errors import BindingFileError
from kitchen_tamp.planning.loading import domain_model
from kitchen_tamp.planning.schemas import DomainModel

BINDING_SUFFIX: Final = ".binding.toml"
SECTIONS: Final = ("types", "predicates", "actions")


def binding_path_for(domain: Path) -> Path:
    """Where the binding of ``domain`` is: ``<stem>.binding.toml`` beside the file it resolves to."""
    resolved = domain.resolve()
    return resolved.with_name(resolved.stem + BINDING_SUFFIX)


def read_binding(domain: Path) -> DomainBinding:
    """The checked binding of ``domain``; raises ``BindingFileError`` naming the file and key
    (``PlanningInputError`` for a bad domain file)."""
    path = binding_path_for(domain)
    model = domain_model(domain)
    if not path.is_file():
        raise BindingFileError(
            path, "", f"no skill binding for domain {model.name!r} ({domain}): the kitchen needs this file "
            "beside the domain to know which skill carries out each action (see docs/tamp.md)"
        )
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError) as error:
        raise BindingFileError(path, "", f"cannot read the binding: {error}") from None
    except tomllib.TOMLDecodeError as error:
        raise BindingFileError(path, "", f"not valid TOML: {error}") from None
    return parse_binding(path, data, model)


def _table(path: Path, data: dict[str, Any], key: str) -> dict[str, Any]:
    value = data.get(key, {})
    if not isinstance(value, dict):
        raise BindingFileError(path, key, f"expected a table, got {type(value).__name__}")
    return value


def parse_binding(path: Path, data: dict[str, Any], model: DomainModel) -> DomainBinding:
    """The binding a parsed TOML file gives ``model``'s domain."""
    for key in data:
        if key not in SECTIONS:
            raise BindingFileError(path, key, f"unknown section (sections: {', '.join(SECTIONS)})")
    return DomainBinding(
        path=path,
        domain=model.name,
        types=MappingProxyType(_types(path, _table(path, data, "types"), model)),
        type_ancestors=MappingProxyType(dict(model.ancestors)),
        predicates=MappingProxyType(_predicates(path, _table(path, data, "predicates"), model)),
        actions=MappingProxyType(_actions(path, _table(path, data, "actions"), model)),
    )


def _types(path: Path, table: dict[str, Any], model: DomainModel) -> dict[str, str]:
    """Kind or region kind -> the domain's type (a key that is no kind names a region kind)."""
    types = {}
    for kind, value in table.items():
        key = f"types.{kind}"
        if not isinstance(value, str):
            raise BindingFileError(path, key, f"expected the name of a type of the domain, got {value!r}")
        declared = model.type_names.get(value)
        if declared is None:
            raise BindingFileError(path, key, f"the domain has no type {value!r}")
        types[kind] = declared
    return types


def _predicates(path: Path, table: dict[str, Any], model: DomainModel) -> dict[str, tuple[str, ...]]:
    meanings: dict[str, tuple[str, ...]] = {}
    for name, value in table.items():
        key = f"predicates.{name}"
        declared = model.predicate_names.get(name)
        if declared is None:
            raise BindingFileError(path, key, f"the domain has no predicate {name!r}")
        relations = [value] if isinstance(value, str) else value
        if not isinstance(relations, list) or not relations or not all(isinstance(r, str) for r in relations):
            raise BindingFileError(path, key, f"expected a relation or a list of relations, got {value!r}")
        arity = model.predicates[declared]
        for relation in relations:
            if relation not in RELATIONS:
                raise BindingFileError(
                    path, key, f"unknown relation {relation!r} (relations: {', '.join(RELATIONS)})"
                )
            if len(RELATIONS[relation]) != arity:
                raise BindingFileError(
                    path, key, f"{relation} relates {len(RELATIONS[relation])} objects, "
                    f"the domain's {declared} takes {arity}"
                )
        meanings[declared] = tuple(relations)
    for declared in model.predicates:
        if declared not in meanings:
            raise BindingFileError(
                path, "predicates", f"missing predicate {declared!r} of the domain: every predicate needs "
                "the relation Ψ derives it from"
            )
    return meanings


def _actions(path: Path, table: dict[str, Any], model: DomainModel) -> dict[str, ActionBinding]:
    schemas = {action.name.lower(): action for action in model.actions}
    bindings: dict[str, ActionBinding] = {}
    for name, value in table.items():
        key = f"actions.{name}"
        schema = schemas.get(name.lower())
        if schema is None:
            raise BindingFileError(path, key, f"the domain has no action {name!r}")
        if not isinstance(value, dict):
            raise BindingFileError(path, key, f"expected a table (skill and roles), got {value!r}")
        skill = value.get("skill")
        if not isinstance(skill, str) or skill not in SKILL_ROLES:
            raise BindingFileError(
                path, f"{key}.skill", f"unknown skill {skill!r} (skills: {', '.join(SKILL_ROLES)})"
            )
        roles = SKILL_ROLES[skill]
        parameters = list(schema.parameters)
        played: dict[str, int] = {}
        for role, parameter in value.items():
            if role == "skill":
                continue
            if roles.kinds(role) is None:
                raise BindingFileError(
                    path, f"{key}.{role}", f"unknown key (roles of {skill}: {', '.join(roles.names)})"
                )
            if not isinstance(parameter, str) or parameter.lower() not in [p.lower() for p in parameters]:
                raise BindingFileError(
                    path, f"{key}.{role}", f"{parameter!r} is not a parameter of {schema.name} "
                    f"(its parameters: {', '.join(parameters) or 'none'})"
                )
            played[role] = [p.lower() for p in parameters].index(parameter.lower())
        for role in roles.required:
            if role not in played:
                raise BindingFileError(path, key, f"missing role {role!r} of skill {skill}")
        bindings[schema.name] = ActionBinding(
            schema.name, skill, MappingProxyType(played), schema.parameter_types
        )
    for schema in model.actions:
        if schema.name not in bindings:
            raise BindingFileError(
                path, f"actions.{schema.name}", f"the domain's action {schema.name!r} has no skill binding"
            )
    return bindings
