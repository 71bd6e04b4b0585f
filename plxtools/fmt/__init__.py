"""fmt layer."""
