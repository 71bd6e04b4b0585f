"""U: names of another OpenPLX version, found with the API index of every official version."""

from plxtools.rules.catalog.pages import doc

doc("OLDER_NAME",
    "A model or trait is written with the name it had in an older OpenPLX version; the version in use "
    "has it under another name (it moved to another namespace, or was renamed one to one).",
    "The change comes from plx's index of every official `openplx-bundles` version, or from its reviewed "
    "table of renames, so the new name is the same model. The safe fix writes it; `plx migrate --to "
    "VERSION` does it for whole files, together with renamed attributes.",
    example="geometry is Physics3D.Charges.Box:   # written for 0.17",
    use_instead="geometry is Physics3D.Geometries.Box:")

doc("RENAMED_ATTRIBUTE",
    "An attribute is written with the name it had in an older OpenPLX version (`charges` before "
    "`connectors`); the version in use renamed it.",
    "The index of every official version (or its reviewed table) records the rename and the models it "
    "applies to. The fix is unsafe: plx knows which models renamed the attribute, and you confirm that "
    "the object here is one of them. `plx migrate --to VERSION` renames it through the model, where the "
    "owner is known.",
    example="hinge is Physics3D.Interactions.Hinge:\n    charges: [a.top, b.top]   # written for 0.17",
    use_instead="hinge is Physics3D.Interactions.Hinge:\n    connectors: [a.top, b.top]")
