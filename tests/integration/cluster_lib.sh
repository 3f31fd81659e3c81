# Helpers for the cluster integration tests (sourced; not a test itself).
# Every test gets its own folder and an ephemeral port, so tests can run in parallel.
set -euo pipefail
build=$(cd "${1:?usage: $0 BUILD_DIR}" && pwd)
tmp=$(mktemp -d "${TMPDIR:-/tmp}/cavelight-cluster.XXXXXX")
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill -CONT "$p" 2>/dev/null || true; kill "$p" 2>/dev/null || true; done
  wait 2>/dev/null || true
  rm -rf "$tmp"
}
trap cleanup EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# make_config FILE BARRIER_MS NODE...: one CAVE half-wall per node, 32x64 pixels, stereo.
# MASTER_MS (default 3000) sets timeouts.master_ms; MASTER_MS= leaves it to its default.
make_config() {
  local file=$1 barrier=$2; shift 2
  local screens=(front-l front-r left-f right-f floor-f) i=0 nodes="" master_ms=""
  [ -z "${MASTER_MS-3000}" ] || master_ms=" \"master_ms\": ${MASTER_MS-3000},"
  for n in "$@"; do
    nodes+="${nodes:+,}{\"name\": \"$n\", \"screens\": [\"${screens[$i]}\"], \"resolution\": [32, 64], \"eyes\": \"stereo\", \"output\": \"headless\"}"
    i=$((i + 1))
  done
  cat > "$file" <<JSON
{"name": "test", "master": {"bind": "tcp://127.0.0.1:1", "connect": "tcp://127.0.0.1:1"},
 "security": {"mode": "${CLUSTER_SECURITY:-insecure}"},
 "timeouts": {"barrier_ms": $barrier, "heartbeat_ms": 100, "join_ms": ${JOIN_MS:-60000},${master_ms} "stall_min_ms": ${STALL_MIN_MS:-$barrier}},
 "observer": {"eye_separation": 0.064, "home": [0, 1.7, 0]},
 "settings": {${SETTINGS-\"lattice\": 16, \"rsm\": 64}},
 "screens": [
  {"name": "front-l", "bottom_left": [-1.5,0,-1.5], "bottom_right": [0,0,-1.5], "top_left": [-1.5,3,-1.5], "overview": [32, 0]},
  {"name": "front-r", "bottom_left": [0,0,-1.5], "bottom_right": [1.5,0,-1.5], "top_left": [0,3,-1.5], "overview": [64, 0]},
  {"name": "left-f", "bottom_left": [-1.5,0,0], "bottom_right": [-1.5,0,-1.5], "top_left": [-1.5,3,0], "overview": [0, 0]},
  {"name": "right-f", "bottom_left": [1.5,0,-1.5], "bottom_right": [1.5,0,0], "top_left": [1.5,3,-1.5], "overview": [96, 0]},
  {"name": "floor-f", "bottom_left": [-1.5,0,0], "bottom_right": [1.5,0,0], "top_left": [-1.5,0,-1.5]}],
 "nodes": [$nodes]}
JSON
}

# json EXPR FILE: evaluates a Python expression over the parsed JSON as r.
json() { python3 -c "import json,sys; r=json.load(open(sys.argv[2])); print($1)" "$1" "$2"; }

# wait_for_file FILE SECONDS
wait_for_file() {
  for _ in $(seq $(( $2 * 10 ))); do [ -s "$1" ] && return 0; sleep 0.1; done
  fail "$1 did not appear within $2 s"
}

# Node options that keep a 2-core machine responsive with several nodes (the configs'
# "settings" keep the lattice and the RSM small, make_config).
small_render="--threads 1"
