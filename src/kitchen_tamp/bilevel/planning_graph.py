"""The bilevel planning graph a planner builds, kept as a record for reports and pictures.

Low-level state nodes are numbered (states themselves need not be hashable);
abstract state nodes are the abstract states. Abstractor edges link each state
node to Psi of its state, action edges carry the sampled trajectory between two
state nodes, and abstract action edges are the abstract transitions the planner
tried to refine, with how many samples each took and how many failed. Every
node, edge and failed sample carries the number of the sample that made it
(0 for the initial state), so the growth of the graph can be replayed.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Generic, TypeVar

from kitchen_tamp.bilevel.abstraction import AbstractTransition
from kitchen_tamp.bilevel.problem import SamplingFailure
from kitchen_tamp.bilevel.trajectory import Trajectory

X = TypeVar("X")
U = TypeVar("U")
S = TypeVar("S")
A = TypeVar("A")


@dataclass(frozen=True, eq=False)
class StateNode(Generic[X]):
    """A low-level state reached by the planner."""

    id: int
    state: X
    sample: int


@dataclass(frozen=True)
class AbstractorEdge(Generic[S]):
    """Psi(state of node ``state_node``) == ``abstract_state``."""

    state_node: int
    abstract_state: S


@dataclass(frozen=True, eq=False)
class ActionEdge(Generic[X, U, S, A]):
    """A sampled trajectory from state node ``source`` to state node ``target`` realising ``transition``."""

    source: int
    target: int
    transition: AbstractTransition[S, A]
    trajectory: Trajectory[X, U]
    sample: int


@dataclass
class AbstractActionEdge(Generic[S, A]):
    """An abstract transition the planner tried to refine, and how that went so far."""

    transition: AbstractTransition[S, A]
    first_sample: int
    samples: int = 0
    failures: int = 0


@dataclass(frozen=True, eq=False)
class FailedSample(Generic[S, A]):
    """A sample that did not realise ``transition`` from state node ``source``, and why."""

    source: int
    transition: AbstractTransition[S, A]
    error: SamplingFailure
    sample: int

    @property
    def message(self) -> str:
        return str(self.error)


class PlanningGraph(Generic[X, U, S, A]):
    """The record: nodes and edges in the order they were added."""

    def __init__(self) -> None:
        self.state_nodes: list[StateNode[X]] = []
        self.abstract_states: list[S] = []
        self.abstractor_edges: list[AbstractorEdge[S]] = []
        self.action_edges: list[ActionEdge[X, U, S, A]] = []
        self.failed_samples: list[FailedSample[S, A]] = []
        self._abstract_edges: dict[AbstractTransition[S, A], AbstractActionEdge[S, A]] = {}
        self._incoming: dict[int, ActionEdge[X, U, S, A]] = {}
        self._nodes_by_abstract_state: dict[S, list[int]] = {}

    @property
    def abstract_action_edges(self) -> list[AbstractActionEdge[S, A]]:
        return list(self._abstract_edges.values())

    def add_state(self, state: X, abstract_state: S, sample: int) -> int:
        """Add a state node and its abstractor edge; return the node's id."""
        node = StateNode(len(self.state_nodes), state, sample)
        self.state_nodes.append(node)
        if abstract_state not in self._nodes_by_abstract_state:
            self.abstract_states.append(abstract_state)
            self._nodes_by_abstract_state[abstract_state] = []
        self._nodes_by_abstract_state[abstract_state].append(node.id)
        self.abstractor_edges.append(AbstractorEdge(node.id, abstract_state))
        return node.id

    def abstract_edge(self, transition: AbstractTransition[S, A], sample: int) -> AbstractActionEdge[S, A]:
        """The abstract action edge of ``transition``, added on first use."""
        edge = self._abstract_edges.get(transition)
        if edge is None:
            edge = AbstractActionEdge(transition, first_sample=sample)
            self._abstract_edges[transition] = edge
        return edge

    def add_action_edge(self, edge: ActionEdge[X, U, S, A]) -> None:
        if edge.target in self._incoming:
            raise ValueError(f"state node {edge.target} already has an incoming action edge")
        self.action_edges.append(edge)
        self._incoming[edge.target] = edge

    def add_failed_sample(self, failed: FailedSample[S, A]) -> None:
        self.failed_samples.append(failed)

    def state(self, node: int) -> X:
        return self.state_nodes[node].state

    def abstract_state_of(self, node: int) -> S:
        return self.abstractor_edges[node].abstract_state

    def nodes_in(self, abstract_state: S) -> list[int]:
        """The state nodes whose state abstracts to ``abstract_state``, oldest first."""
        return list(self._nodes_by_abstract_state.get(abstract_state, ()))

    def path_to(self, node: int) -> list[ActionEdge[X, U, S, A]]:
        """The action edges from the initial state node to ``node``."""
        edges: list[ActionEdge[X, U, S, A]] = []
        while node in self._incoming:
            edge = self._incoming[node]
            edges.append(edge)
            node = edge.source
        return list(reversed(edges))
