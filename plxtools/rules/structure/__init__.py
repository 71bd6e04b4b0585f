"""Rule modules about model structure: declarations, `becomes`, inheritance (the `M` codes the checker finds)."""
