# Sourced by the scripts a user starts (setup, build, run, test): `say` tells a
# terminal what is happening ("building ...", "running ..."), and `talkative` says
# whether to; where stderr is not a terminal, or CI=true, they stay quiet (logs).
talkative() { [ -t 2 ] && [ "${CI:-}" != true ]; }
say() { if talkative; then echo "$*" >&2; fi; }
