"""The rules layer, between the semantic model and the commands (lint, fmt, check, ide).

It holds every rule's code and documentation (`registry`, `catalog/`, one module per family),
the rules that judge a resolved file (`completeness`, `style`), inline suppressions, the one
pipeline that turns a parsed file into its final diagnostics (`analysis`), and the output
formats (`reporters`)."""
