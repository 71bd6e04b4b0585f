"""`plx migrate`: move model files between official OpenPLX versions (`--to`), or explain the changes (`--explain`)."""
