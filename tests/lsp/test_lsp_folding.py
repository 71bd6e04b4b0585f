"""Folding ranges over stdio."""

from __future__ import annotations

import pytest
from lsprotocol import types

from tests.lsp.conftest import EXAMPLE_URI, example_text, open_and_wait

pytestmark = [pytest.mark.asyncio(loop_scope="module"),
              pytest.mark.filterwarnings("error::pytest_lsp.LspSpecificationWarning")]


async def test_folding_ranges(client):
    text = example_text()
    await open_and_wait(client, EXAMPLE_URI, text)
    folds = await client.text_document_folding_range_async(types.FoldingRangeParams(
        text_document=types.TextDocumentIdentifier(uri=EXAMPLE_URI)))
    truck = text[:text.index("BoxTruck is")].count("\n")
    assert any(f.start_line == truck and f.end_line > truck for f in folds)
    assert any(f.kind == types.FoldingRangeKind.Comment for f in folds)
