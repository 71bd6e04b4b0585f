"""Rule modules about bundles and their dependencies (the `B` codes)."""
