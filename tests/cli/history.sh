#!/usr/bin/env bash
# `history add|show|check` against SQLite, or (HISTORY_BACKEND=postgresql, the test
# cli-history_pg) against a PostgreSQL server this test starts itself (initdb and pg_ctl
# in its scratch folder, a unix socket only; as the `postgres` user when run as root,
# since initdb refuses root). Hand-made folders with known numbers, no GL: twelve
# sweeps of six runs, run 3 +20% from sweep 6 on. Two adds at the same time into a new
# database, then two more: nothing lost; a folder added again adds nothing; check finds
# the one regression at its sweep (exit 1) and none on the other runs (exit 0); the
# JSON's fields; a database of another schema version refused with both versions named.
. "$(dirname "$0")/lib.sh"
backend=${HISTORY_BACKEND:-sqlite}
cd "$T"
if [ "$backend" = postgresql ]; then
  bin=$(ls -d /usr/lib/postgresql/*/bin 2>/dev/null | sort -V | tail -1 || true)
  if [ -z "$bin" ] || [ ! -x "$bin/initdb" ]; then
    echo "SKIP: no PostgreSQL server (initdb) installed: scripts/setup.sh installs postgresql" >&2
    exit 77
  fi
  as=()
  if [ "$(id -u)" -eq 0 ]; then
    as=(runuser -u postgres --)
    chmod 711 "$T"
  fi
  mkdir "$T/pg"
  [ ${#as[@]} -eq 0 ] || chown postgres "$T/pg"
  "${as[@]}" "$bin/initdb" -D "$T/pg/data" -U postgres --auth=trust >"$T/initdb.log" 2>&1 ||
    fail "initdb: $(cat "$T/initdb.log")"
  "${as[@]}" "$bin/pg_ctl" -D "$T/pg/data" -l "$T/pg/log" -w -t 60 \
    -o "-c listen_addresses= -k $T/pg -p 5432 -c fsync=off" start >/dev/null ||
    fail "pg_ctl start: $(cat "$T/pg/log")"
  trap '"${as[@]}" "$bin/pg_ctl" -D "$T/pg/data" -m immediate stop >/dev/null 2>&1; rm -rf "$T"' EXIT
  DB="postgresql:///postgres?host=$T/pg&port=5432&user=postgres"
  sql() { "$bin/psql" -X -q -t -A "$DB" -c "$1"; }
else
  DB="$T/h.sqlite"
  sql() { "$PYTHON" -c 'import sqlite3, sys
c = sqlite3.connect(sys.argv[1])
for r in c.execute(sys.argv[2]): print("|".join(map(str, r)))
c.commit()' "$DB" "$1"; }
fi
H() { "$SHADESWEEP" history "$@" --db "$DB"; }

"$PYTHON" - <<'PY'
import csv, os, random
random.seed(41)
runs = ["run%08d" % i for i in range(6)]
for s in range(12):
    d = "s%02d" % s
    os.makedirs(d)
    with open(f"{d}/summary.csv", "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["experiment", "run_id", "renderer", "trial", "frametime_mean_us",
                    "cpu_mean_us", "gpu_mean_us", "metric", "metric_us", "status"])
        for i, rid in enumerate(runs):
            for k in (1, 2, 3):
                x = 1000 * (i + 1) * (1.2 if i == 3 and s >= 6 else 1) * random.gauss(1, 0.01)
                w.writerow(["h", rid, "r%d" % i, k, "%.3f" % (x * 1.1), "%.3f" % x, "",
                            "cpu", "%.3f" % x, "ok"])
    for i, rid in enumerate(runs):
        os.makedirs(f"{d}/runs/{rid}")
        with open(f"{d}/runs/{rid}/meta.yaml", "w") as f:
            f.write(f"""run_id: "{rid}"
manifest:
  hash: "feedface{s:08d}"
shadesweep:
  commit: c{s:06d}
  dirty: false
gl:
  vendor: V
  renderer: "R (x)"
  version: "4.5"
host:
  hostname: ci
  cpu: C
schedule:
  point: {i}
trials:
  - trial: 1
    started: "2026-12-{s + 1:02d}T10:00:0{i}Z"
""")
PY

# two adds at once into a new database (both would make its tables), then two more
# into the tables they made, three folders each: all complete, nothing lost
(H add s00 s01 s02 >add1.out 2>add1.err; echo $? >add1.rc) &
(H add s03 s04 s05 >add2.out 2>add2.err; echo $? >add2.rc) &
wait
[ "$(cat add1.rc)$(cat add2.rc)" = 00 ] || fail "first adds at once: $(cat add1.err add2.err)"
grep -q "^s05: 6 runs and 18 trials added to " add2.out || fail "add: $(cat add2.out)"
(H add s06 s07 s08 >add1.out 2>add1.err; echo $? >add1.rc) &
(H add s09 s10 s11 >add2.out 2>add2.err; echo $? >add2.rc) &
wait
[ "$(cat add1.rc)$(cat add2.rc)" = 00 ] || fail "concurrent adds: $(cat add1.err add2.err)"
[ "$(sql 'SELECT count(*) FROM trials')" = 216 ] || fail "trials: $(sql 'SELECT count(*) FROM trials')"
[ "$(sql 'SELECT count(*) FROM runs')" = 72 ] || fail "runs"
[ "$(sql 'SELECT count(*) FROM sweeps')" = 12 ] || fail "sweeps"
# provenance
[ "$(sql "SELECT date, commit_id, dirty, host, device, manifest_hash FROM sweeps WHERE date LIKE '2026-12-07%'")" = \
  "2026-12-07T10:00:00Z|c000006|0|ci (C)|V | R (x) | 4.5|feedface00000006" ] ||
  fail "provenance: $(sql 'SELECT * FROM sweeps')"
[ "$(sql "SELECT point, metric, status FROM runs WHERE run_id = 'run00000004' LIMIT 1")" = "4|cpu|ok" ] ||
  fail "run row"
# again: nothing added twice
H add s03 >again.out 2>&1 || fail "add again: $(cat again.out)"
grep -q "^s03: 0 runs and 0 trials added to .* (all there already)$" again.out || fail "again: $(cat again.out)"
[ "$(sql 'SELECT count(*) FROM trials')" = 216 ] || fail "trials after a second add"

# check: the one regression, at sweep 6, exit 1
rc=0; H check --json cp.json >check.out 2>check.err || rc=$?
[ $rc -eq 1 ] || fail "check: exit $rc, want 1: $(cat check.out check.err)"
grep -q "^1 change points: 1 regressions, 0 improvements$" check.out || fail "check: $(cat check.out)"
grep -q "^| run00000003 | r3 | cpu | 2026-12-07T10:00:00Z | c000006 | 4\.0[0-9]* | 4\.[78][0-9]* | +[12][0-9]\.[0-9]% | .* | \*\*regression\*\* |$" check.out ||
  fail "check row: $(cat check.out)"
"$PYTHON" - cp.json <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
assert j["schema"] == "shadesweep-history" and j["sweeps"] == 12 and j["runs"] == 6, j
assert j["regressions"] == 1 and len(j["change_points"]) == 1, j
c = j["change_points"][0]
for k in ("time", "metric", "forward_change_percent", "magnitude", "mean_before",
          "mean_after", "stddev_before", "stddev_after", "pvalue", "prev_value",
          "new_value", "amount_pct", "t_value", "is_regression"):
    assert k in c, k
assert c["run_id"] == "run00000003" and c["index"] == 6 and c["is_regression"] is True, c
assert 17 < c["forward_change_percent"] < 23 and c["pvalue"] < 0.001 and c["t_value"] > 5, c
assert c["prev_value"] == c["mean_before"] and abs(c["amount_pct"] - c["forward_change_percent"]) < 1e-9
PY
# the other runs: no change point, exit 0; a filter by renderer
H check --run run00000002 >c2.out 2>&1 || fail "check run 2: $(cat c2.out)"
grep -q "^0 change points" c2.out || fail "run 2: $(cat c2.out)"
rc=0; H check --renderer r3 --metric wall >c3.out 2>&1 || rc=$?
[ $rc -eq 1 ] || fail "r3 wall: exit $rc: $(cat c3.out)"
# the floor: a 20% step is not a change over 25%
H check --min-change 25% >c4.out 2>&1 || fail "min-change 25%: $(cat c4.out)"
H show >show.out 2>&1 || fail "show: $(cat show.out)"   # show exits 0 with a regression
grep -q "regression" show.out || fail "show: $(cat show.out)"
expect 2 "bad value 'x' for --min-change" H check --min-change x
expect 2 "bad value 'foo' for --metric" H show --metric foo
expect 2 "--run or --renderer, not both" H show --run a --renderer b
if [ "$backend" = sqlite ]; then   # the default: beside the folders, in their parent
  mkdir out && cp -r s00 out/
  "$SHADESWEEP" history add out/s00 >def.out 2>&1 || fail "default db: $(cat def.out)"
  grep -q "^out/s00: 6 runs and 18 trials added to out/history.sqlite$" def.out &&
    [ -f out/history.sqlite ] || fail "default db: $(cat def.out)"
  "$SHADESWEEP" history show >def.out 2>&1 || fail "show, default db: $(cat def.out)"
  grep -q "^history out/history.sqlite: 1 sweeps, 6 runs, 0 series" def.out || fail "$(cat def.out)"
fi

# another schema version: refused, naming both
sql "UPDATE shadesweep_history SET version = 99" >/dev/null
expect 2 "the database has schema version 99, this shadesweep reads and writes version 1" H check
expect 2 "the database has schema version 99, this shadesweep reads and writes version 1" H add s00
[ "$(sql 'SELECT count(*) FROM trials')" = 216 ] || fail "a refused add wrote"
echo ok
