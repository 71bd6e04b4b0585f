"""The rules layer, between the semantic model and the commands (lint, fmt, check, ide).

`registry` is the one list of codes (code, name, severity, stage, fix, tags, owns, module); a rule
in the module form lives in `<family>/<rule>.py` (its docstring is its page, its `check(facts,
report)` its findings) and `engine` runs those modules; the rules not moved yet are `style`,
`literals` and those raised in `syntax/`, `model/` and `check/`, with their pages in `catalog/`. `analysis` is the one pipeline that turns a
parsed file into its final diagnostics (registry severity, config, follow-on findings, owned codes,
suppressions, order) for lint, check and the server; `reporters` writes the output formats."""
