#pragma once
/* The command line: run, validate, list, info. Returns the process exit code:
 * 0 success; 1 some run failed; 2 bad input or a fatal error (message printed). */
int cli_main(int argc, char **argv);
