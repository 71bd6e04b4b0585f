"""Rules in the module form about names, types and model structure (one module per rule)."""
