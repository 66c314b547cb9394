"""What a domain's symbols mean in the simulated kitchen.

A kitchen is one scene file; its models and its map of symbols to geometry are
derived from it, and the domain's binding (``binding``: types, predicates as
geometric relations, actions as skills with roles) is read beside the domain
(``load_kitchen_map``; the shipped default kitchen with the kitchen domain is
``default_kitchen_map``). Build the scene for a problem (``build_kitchen_for_task``),
read its symbolic state back (``abstract_state``, Ψ), and turn each grounded action
into motion targets (``sample_targets`` / ``sample_action_targets`` -> ``SkillTargets``,
or a ``SkillFailure`` saying why and which objects obstruct).
"""

from kitchen_tamp.kitchen.abstraction import RESTING_GAP, abstract_state, check_initial_state
from kitchen_tamp.kitchen.action_replay import ActionReplay, first_problem, replay_action
from kitchen_tamp.kitchen.binding import ActionBinding, DomainBinding
from kitchen_tamp.kitchen.binding_reader import read_binding
from kitchen_tamp.kitchen.conditions import apply_condition_effects, record_conditions
from kitchen_tamp.kitchen.contact_policy import CONTACT_PENETRATION_BOUND, check_initial_overlaps
from kitchen_tamp.kitchen.errors import (
    BindingFileError,
    FailureKind,
    InitialStateMismatchError,
    KitchenError,
    SkillFailure,
    UnknownActionError,
    UnknownObjectError,
    UnsupportedInitialStateError,
)
from kitchen_tamp.kitchen.replay_track import Carried, SegmentTrack
from kitchen_tamp.kitchen.scene.kitchen_map import KitchenMap, default_kitchen_map, load_kitchen_map
from kitchen_tamp.kitchen.scene.kitchen_scene import KitchenScene
from kitchen_tamp.kitchen.scene.layout import build_kitchen, build_kitchen_for_task, load_kitchen_problem
from kitchen_tamp.kitchen.scene.regions import SupportRegion
from kitchen_tamp.kitchen.scene.spec_reader import SceneFileError
from kitchen_tamp.kitchen.segment import Segment
from kitchen_tamp.kitchen.skills.grasps import Grasp
from kitchen_tamp.kitchen.skills.parameters import DEFAULT_PARAMETERS, SkillParameters
from kitchen_tamp.kitchen.skills.placements import Placement
from kitchen_tamp.kitchen.skills.registry import SKILLS, sample_action_targets, sample_targets
from kitchen_tamp.kitchen.skills.targets import SkillTargets

__all__ = [
    "CONTACT_PENETRATION_BOUND",
    "DEFAULT_PARAMETERS",
    "RESTING_GAP",
    "SKILLS",
    "ActionBinding",
    "ActionReplay",
    "BindingFileError",
    "Carried",
    "DomainBinding",
    "FailureKind",
    "Grasp",
    "InitialStateMismatchError",
    "KitchenError",
    "KitchenMap",
    "KitchenScene",
    "Placement",
    "SceneFileError",
    "Segment",
    "SegmentTrack",
    "SkillFailure",
    "SkillParameters",
    "SkillTargets",
    "SupportRegion",
    "UnknownActionError",
    "UnknownObjectError",
    "UnsupportedInitialStateError",
    "abstract_state",
    "apply_condition_effects",
    "build_kitchen",
    "build_kitchen_for_task",
    "check_initial_overlaps",
    "check_initial_state",
    "default_kitchen_map",
    "first_problem",
    "load_kitchen_map",
    "load_kitchen_problem",
    "read_binding",
    "record_conditions",
    "replay_action",
    "sample_action_targets",
    "sample_targets",
]
