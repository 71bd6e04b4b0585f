"""The language knowledge behind the editor features, as plain functions: offsets in, data out.

Nothing here imports pygls or speaks LSP; `plxtools.lsp` translates. Tests call these directly:

    host = AnalysisHost()
    host.open_document(path, text, version=1)
    st = host.state(path)                     # parse + check + lint, cached per version
    hover(st, offset); definition(st, offset); complete(st, offset); ...
"""

from plxtools.ide.actions import code_actions, fix_all, suppress_edit
from plxtools.ide.completion import complete, complete_line, completion_documentation
from plxtools.ide.formatting import FormattingRefused, format_document, format_lines
from plxtools.ide.host import AnalysisHost, FileState, Settings
from plxtools.ide.hover import hover
from plxtools.ide.inlay import inlay_hints
from plxtools.ide.navigation import declaration, definition, prepare_rename, references, rename, type_definition
from plxtools.ide.outline import document_links, document_symbols, folding_ranges, workspace_symbols
from plxtools.ide.signature import signature_help
from plxtools.ide.tokens import TOKEN_MODIFIERS, TOKEN_TYPES, semantic_tokens
from plxtools.ide.types import RenameError

__all__ = [
    "AnalysisHost", "FileState", "FormattingRefused", "RenameError", "Settings", "TOKEN_MODIFIERS", "TOKEN_TYPES",
    "code_actions", "complete", "complete_line", "completion_documentation", "declaration", "definition", "document_links",
    "document_symbols", "fix_all", "folding_ranges", "format_document", "format_lines", "hover", "inlay_hints",
    "prepare_rename", "references", "rename", "semantic_tokens", "signature_help", "suppress_edit",
    "type_definition", "workspace_symbols",
]
