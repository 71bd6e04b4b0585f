"""Plain data the ide functions return: paths, spans (0-based lines, columns in code points), text.

The language server turns these into LSP objects; tests compare them directly.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from plxtools.diagnostics import Span


@dataclass(frozen=True, slots=True)
class FileSpan:
    path: str
    span: Span


@dataclass(slots=True)
class NavTarget:
    """Where a symbol is defined: the name (`focus`) and the whole statement (`full`)."""

    path: str
    focus: Span
    full: Span
    name: str


@dataclass(slots=True)
class HoverResult:
    markdown: str
    span: Span


@dataclass(slots=True)
class TextEdit:
    start: int  # offsets in the file's text
    end: int
    text: str


@dataclass(slots=True)
class CompletionItem:
    label: str
    kind: str  # "model" | "trait" | "namespace" | "attribute" | "method" | "keyword" | "value" | "constant" | "type"
    detail: str = ""
    documentation: str | None = None  # filled lazily by completion_documentation when None
    insert_text: str | None = None
    snippet: bool = False
    sort_text: str | None = None
    filter_text: str | None = None
    deprecated: bool = False
    key: object = None  # what completion_documentation needs to describe the item
    label_detail: str | None = None
    label_description: str | None = None


@dataclass(slots=True)
class CompletionResult:
    items: list[CompletionItem]
    replace_start: int  # offsets of the word being completed
    replace_end: int
    is_incomplete: bool = False


@dataclass(slots=True)
class ParameterInfo:
    label: str
    documentation: str | None = None


@dataclass(slots=True)
class SignatureInfo:
    label: str
    parameters: list[ParameterInfo]
    documentation: str | None = None


@dataclass(slots=True)
class SignatureHelpResult:
    signatures: list[SignatureInfo]
    active_signature: int = 0
    active_parameter: int = 0


@dataclass(slots=True)
class SymbolInfo:
    name: str
    kind: str  # "model" | "trait" | "const" | "global" | "attribute" | "method" | "operator" | "block" | "import"
    span: Span  # the whole statement
    selection: Span  # the name
    detail: str = ""
    children: list["SymbolInfo"] = field(default_factory=list)
    deprecated: bool = False


@dataclass(slots=True)
class WorkspaceSymbolInfo:
    name: str
    kind: str
    path: str
    span: Span
    container: str = ""


@dataclass(slots=True)
class RenameError(Exception):
    message: str

    def __str__(self) -> str:
        return self.message


@dataclass(slots=True)
class CodeAction:
    title: str
    kind: str  # "quickfix" | "source.fixAll" | "quickfix.suppress"
    edits: dict[str, list[TextEdit]]
    diagnostics: list = field(default_factory=list)  # plxtools Diagnostics it resolves
    preferred: bool = False


@dataclass(slots=True)
class FoldingRange:
    start_line: int
    end_line: int
    kind: str | None = None  # "comment" | "region" | None


@dataclass(slots=True)
class DocumentLink:
    span: Span
    target: str  # an absolute file path
    tooltip: str | None = None


@dataclass(slots=True)
class InlayHint:
    offset: int
    line: int
    column: int
    label: str
    kind: str  # "type" | "parameter"
    padding_left: bool = False
    padding_right: bool = False
    tooltip: str | None = None


@dataclass(frozen=True, slots=True)
class SemanticToken:
    line: int
    column: int  # code points
    length: int  # code points
    type: str
    modifiers: tuple[str, ...] = ()
