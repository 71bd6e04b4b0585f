"""Rule modules about conventions: deprecated attributes, annotations (the `C` codes the checker finds)."""
