"""Rule modules about how a model will assemble, judged from its source (the `A` codes lint reports)."""
