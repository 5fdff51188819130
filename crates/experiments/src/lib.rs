//! Library side of the `usar` command line: argument parsing and the commands.
