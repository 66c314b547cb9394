"""Eight doubles as one value in compiled code: LLVM's ``<8 x double>``, which numba has no type for.

numba leaves vectorising to LLVM, which does not vectorise the lane loops of `screen` (measured: a
chain of link poses, eight configurations a loop, ran at scalar speed whether the loop's length was
fixed, which LLVM unrolls and then cannot pack, or read at run time, where the loads and stores it
cannot prove apart keep it scalar). `Doubles8` is that vector as a numba type: loaded from and stored
to a float64 array, combined with ``+``, ``-``, ``*``, ``/`` and unary ``-`` (with another
`Doubles8` or a number, broadcast), and compared into a bit mask (bit ``k`` for lane ``k``, an
ordinary integer). The same chain of poses runs 4.6 times faster written with it.

Every function here is an intrinsic: LLVM sees the vector instructions themselves, inlined into
the caller, and compiles them for the machine (AVX-512 in two halves on this one, two or four
SSE/AVX registers elsewhere).
"""

from __future__ import annotations

import operator
from collections.abc import Callable
from typing import Any

from llvmlite import ir  # type: ignore[import-untyped]
from numba.core import cgutils, types
from numba.extending import intrinsic, models, overload, register_model

WIDTH = 8
"""Lanes of a `Doubles8`."""

_VECTOR = ir.VectorType(ir.DoubleType(), WIDTH)
_INT32 = ir.IntType(32)


class Doubles8Type(types.Type):
    """numba's type of eight doubles in one LLVM vector."""

    def __init__(self) -> None:
        super().__init__(name="Doubles8")


doubles8 = Doubles8Type()


@register_model(Doubles8Type)
class _Doubles8Model(models.PrimitiveModel):
    def __init__(self, dmm: Any, fe_type: Any) -> None:
        super().__init__(dmm, fe_type, _VECTOR)  # type: ignore[no-untyped-call]


def _compiled(typer: Callable[..., Any]) -> Any:
    """``typer`` as a numba intrinsic (typed as Any for mypy: numba's stubs would have every call
    pass the typing context)."""
    return intrinsic(typer)


def _element_pointer(context: Any, builder: Any, array_type: Any, array: Any, start: Any) -> Any:
    data = context.make_array(array_type)(context, builder, array)
    return builder.gep(data.data, [start])


def _broadcast(context: Any, builder: Any, value: Any, kind: Any) -> Any:
    """A number as eight equal lanes."""
    if kind == doubles8:
        return value
    scalar = context.cast(builder, value, kind, types.float64)
    single = builder.insert_element(ir.Constant(_VECTOR, ir.Undefined), scalar, ir.Constant(_INT32, 0))
    zeros = ir.Constant(ir.VectorType(_INT32, WIDTH), [0] * WIDTH)
    return builder.shuffle_vector(single, ir.Constant(_VECTOR, ir.Undefined), zeros)


@_compiled
def load8(typingctx: Any, array: Any, start: Any) -> Any:
    """array[start : start + 8] (a 1-D contiguous float64 array) as one `Doubles8`."""

    def generate(context: Any, builder: Any, signature: Any, arguments: Any) -> Any:
        pointer = _element_pointer(context, builder, signature.args[0], arguments[0], arguments[1])
        return builder.load(builder.bitcast(pointer, _VECTOR.as_pointer()), align=8)

    return doubles8(array, start), generate


@_compiled
def store8(typingctx: Any, array: Any, start: Any, value: Any) -> Any:
    """array[start : start + 8] = value."""

    def generate(context: Any, builder: Any, signature: Any, arguments: Any) -> Any:
        pointer = _element_pointer(context, builder, signature.args[0], arguments[0], arguments[1])
        builder.store(arguments[2], builder.bitcast(pointer, _VECTOR.as_pointer()), align=8)
        return context.get_dummy_value()

    return types.void(array, start, value), generate


@_compiled
def splat8(typingctx: Any, value: Any) -> Any:
    """``value`` in every lane."""

    def generate(context: Any, builder: Any, signature: Any, arguments: Any) -> Any:
        return _broadcast(context, builder, arguments[0], signature.args[0])

    return doubles8(value), generate


def _binary(result: Any, combine: Callable[[Any, Any, Any], Any]) -> Any:
    """An intrinsic of two operands (each a `Doubles8` or a number, broadcast) whose value, of numba
    type ``result``, ``combine(builder, left, right)`` builds."""

    @_compiled
    def operation(typingctx: Any, a: Any, b: Any) -> Any:
        def generate(context: Any, builder: Any, signature: Any, arguments: Any) -> Any:
            left = _broadcast(context, builder, arguments[0], signature.args[0])
            right = _broadcast(context, builder, arguments[1], signature.args[1])
            return combine(builder, left, right)

        return result(a, b), generate

    return operation


def _arithmetic(instruction: str) -> Any:
    flags = () if instruction == "fdiv" else ("fast",)  # a quotient exact, as the kernel's

    def combine(builder: Any, left: Any, right: Any) -> Any:
        return getattr(builder, instruction)(left, right, flags=flags)

    return _binary(doubles8, combine)


_add, _subtract, _multiply, _divide = (_arithmetic(name) for name in ("fadd", "fsub", "fmul", "fdiv"))


def _is_operand(kind: Any) -> bool:
    return kind == doubles8 or isinstance(kind, (types.Float, types.Integer))


def _binary_overload(python_operator: Any, operation: Any) -> None:
    @overload(python_operator)
    def _typed(a: Any, b: Any) -> Any:
        if (a == doubles8 or b == doubles8) and _is_operand(a) and _is_operand(b):

            def combined(a: Any, b: Any) -> Any:
                return operation(a, b)

            return combined
        return None


for _python, _operation in (
    (operator.add, _add),
    (operator.sub, _subtract),
    (operator.mul, _multiply),
    (operator.truediv, _divide),
):
    _binary_overload(_python, _operation)


@overload(operator.neg)
def _negate(a: Any) -> Any:
    if a == doubles8:

        def negated(a: Any) -> Any:
            return _subtract(0.0, a)

        return negated
    return None


def _vector_function(builder: Any, name: str, arity: int) -> Any:
    """LLVM's intrinsic ``name`` on eight doubles (``llvm.floor.v8f64``), declared in the module."""
    function_type = ir.FunctionType(_VECTOR, [_VECTOR] * arity)
    return cgutils.get_or_insert_function(  # type: ignore[no-untyped-call]
        builder.module, function_type, f"{name}.v{WIDTH}f64"
    )


def _unary_llvm(name: str) -> Any:
    @_compiled
    def operation(typingctx: Any, value: Any) -> Any:
        def generate(context: Any, builder: Any, signature: Any, arguments: Any) -> Any:
            function = _vector_function(builder, name, 1)
            return builder.call(function, [arguments[0]])

        return doubles8(value), generate

    return operation


floor8 = _unary_llvm("llvm.floor")
"""Each lane rounded down."""
sqrt8 = _unary_llvm("llvm.sqrt")
"""Each lane's square root."""
abs8 = _unary_llvm("llvm.fabs")
"""Each lane's magnitude."""


def _binary_llvm(name: str) -> Any:
    def combine(builder: Any, left: Any, right: Any) -> Any:
        return builder.call(_vector_function(builder, name, 2), [left, right])

    return _binary(doubles8, combine)


min8 = _binary_llvm("llvm.minnum")
"""The smaller of two values in each lane."""
max8 = _binary_llvm("llvm.maxnum")
"""The larger of two values in each lane."""


def _comparison(predicate: str) -> Any:
    def combine(builder: Any, left: Any, right: Any) -> Any:
        bits = builder.bitcast(builder.fcmp_ordered(predicate, left, right), ir.IntType(WIDTH))
        return builder.zext(bits, ir.IntType(64))

    return _binary(types.int64, combine)


less8 = _comparison("<")
"""Bit ``k`` set where lane ``k`` of a is below b's."""
at_least8 = _comparison(">=")
"""Bit ``k`` set where lane ``k`` of a is at least b's."""


@_compiled
def lane8(typingctx: Any, value: Any, k: Any) -> Any:
    """Lane ``k`` of ``value`` as a number."""

    def generate(context: Any, builder: Any, signature: Any, arguments: Any) -> Any:
        return builder.extract_element(arguments[0], builder.trunc(arguments[1], _INT32))

    return types.float64(value, k), generate


@_compiled
def gather8(typingctx: Any, array: Any, indices: Any) -> Any:
    """array[indices[k]] in lane ``k`` (a 1-D contiguous array of numbers; ``indices`` whole
    numbers, within the array)."""

    def generate(context: Any, builder: Any, signature: Any, arguments: Any) -> Any:
        array_type = signature.args[0]
        data = context.make_array(array_type)(context, builder, arguments[0]).data
        result = ir.Constant(_VECTOR, ir.Undefined)
        for k in range(WIDTH):
            lane = builder.extract_element(arguments[1], ir.Constant(_INT32, k))
            index = builder.fptosi(lane, ir.IntType(64))
            value = builder.load(builder.gep(data, [index]))
            number = context.cast(builder, value, array_type.dtype, types.float64)
            result = builder.insert_element(result, number, ir.Constant(_INT32, k))
        return result

    return doubles8(array, indices), generate
