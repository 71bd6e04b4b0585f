"""The language server's runtime, as plain Python (no LSP types): when documents are checked
(`scheduler.py`), large documents checked in a forked process (`background.py`), the garbage
collector's policy around checks (`collector.py`), the editor's settings (`settings.py`), and what
the server reports about itself (`stats.py`, `memory.py`). `plxtools.lsp` wires them to the protocol.
"""
