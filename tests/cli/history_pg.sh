#!/usr/bin/env bash
# tests/cli/history.sh against a PostgreSQL server that it starts itself.
HISTORY_BACKEND=postgresql exec bash "$(dirname "$0")/history.sh"
