#pragma once
/* Subcommands that live in their own files; argv[0] is the subcommand's name.
 * Each returns the process exit status. */

/* `shadesweep compare BASE NEW [--threshold P%] [--csv FILE] [--md FILE]`
 * (runner/answer/compare.c): 0 no run significantly slower, 1 some run is, 2 bad input. */
int cmd_compare(int argc, char **argv);

/* `shadesweep report DIR...` (runner/answer/report_cmd.c): runs the Python report
 * (shadesweep_report, installed beside the program) with python3. */
int cmd_report(int argc, char **argv);

/* `shadesweep ratios` (runner/answer/ratios.c): results/verdict.c's ratios, intervals and
 * crossovers for other programs (the Python report), requests on stdin, JSON lines out. */
int cmd_ratios(int argc, char **argv);

/* `shadesweep bound [--profile DEVICE.yaml] DIR` (runner/answer/summary_bound.c): each
 * run's bound from DIR/device.yaml (or the profile named), as CSV on stdout. */
int cmd_bound(int argc, char **argv);
