"""Rule modules about names: members, kinds of type, imports (the `N` codes the model finds)."""
