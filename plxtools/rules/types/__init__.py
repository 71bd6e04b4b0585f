"""Rule modules about values and their types: mismatches, calls, operators, indexing (the `T` codes)."""
