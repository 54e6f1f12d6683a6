"""The vocabulary registry: the single source of truth for functions and channels."""

from matloom.vocab.channels import CHANNELS, PRINT_ORDER
from matloom.vocab.functions import CONSTANTS, FUNCTIONS, LITERALS
from matloom.vocab.spec import (
    REQUIRED,
    ChannelSpec,
    FunctionSpec,
    Kind,
    ParamSpec,
    PrintStyle,
    Returns,
)

__all__ = [
    "CHANNELS",
    "CONSTANTS",
    "FUNCTIONS",
    "LITERALS",
    "PRINT_ORDER",
    "REQUIRED",
    "ChannelSpec",
    "FunctionSpec",
    "Kind",
    "ParamSpec",
    "PrintStyle",
    "Returns",
]
