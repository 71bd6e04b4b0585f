from plxtools.cli import entry

entry()
