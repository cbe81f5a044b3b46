#!/usr/bin/env bash
# The container test: build the image from the Dockerfile, render the built-in demo inside it,
# and check that the clip matches the one the host build renders (ffprobe stream facts); then
# run the image's service and render a still through it over loopback.
#
#   container_test.sh SOURCE_DIR WORK_DIR HOST_DISCREEL
#
# No Docker engine is needed: buildah builds and runs the image (chroot isolation, as root). The
# base image debian:bookworm-slim comes from local storage; when it is missing it is made with
# debootstrap from this machine's own apt mirror and kept for later runs. See docs/container.md.
set -euo pipefail

if [[ $# -ne 3 ]]; then
  echo "usage: $0 SOURCE_DIR WORK_DIR HOST_DISCREEL" >&2
  exit 2
fi
readonly SOURCE_DIR="$1" WORK_DIR="$2" HOST_DISCREEL="$3"
readonly BASE_IMAGE=docker.io/library/debian:bookworm-slim
readonly IMAGE=localhost/discreel:container-test
readonly BUILD_STAGE_IMAGE=localhost/discreel-build:container-test
readonly CONTAINER="discreel-container-test-$$"

fail() {
  echo "container test FAILED: $*" >&2
  exit 1
}

# step NAME COMMAND...: run COMMAND with its output in WORK_DIR/NAME.log; on failure name the
# step, the log, and show the log's end.
step() {
  local name="$1" log="$WORK_DIR/$1.log" start=$SECONDS
  shift
  echo "[$name] $*"
  # A subshell outside any condition, so that `set -e` and `fail` end the step, not the script.
  set +e
  (set -e; "$@") >"$log" 2>&1
  local status=$?
  set -e
  if [[ $status -ne 0 ]]; then
    echo "container test FAILED at step '$name' after $((SECONDS - start)) s; full log: $log" >&2
    echo "----- last 60 lines of $log -----" >&2
    tail -n 60 "$log" >&2
    exit 1
  fi
  echo "[$name] ok in $((SECONDS - start)) s (log: $log)"
}

# The first `deb` source of bookworm itself (not -updates or -security) in apt's own
# configuration, deb822 (*.sources) or one-line (*.list) style.
bookworm_mirror() {
  local mirror=""
  shopt -s nullglob
  local sources=(/etc/apt/sources.list.d/*.sources) lists=(/etc/apt/sources.list /etc/apt/sources.list.d/*.list)
  shopt -u nullglob
  if [[ ${#sources[@]} -gt 0 ]]; then
    mirror="$(awk 'BEGIN { RS = "" }
      /(^|\n)Types:[^\n]*deb([ \t]|\n|$)/ && /(^|\n)Suites:[^\n]*[ \t]bookworm([ \t]|\n|$)/ {
        if (match($0, /(^|\n)URIs:[ \t]*[^ \t\n]+/)) {
          uri = substr($0, RSTART, RLENGTH); sub(/^\n?URIs:[ \t]*/, "", uri); print uri; exit
        }
      }' "${sources[@]}")"
  fi
  if [[ -z $mirror ]]; then
    local list
    for list in "${lists[@]}"; do
      [[ -f $list ]] || continue
      mirror="$(sed -E 's/\[[^]]*\]//' "$list" | awk '$1 == "deb" && $3 == "bookworm" { print $2; exit }')"
      [[ -n $mirror ]] && break
    done
  fi
  echo "${mirror:-http://deb.debian.org/debian}"
}

make_base_image() {
  local mirror rootfs="$WORK_DIR/rootfs"
  mirror="$(bookworm_mirror)"
  echo "debootstrap from $mirror"
  rm -rf "$rootfs"
  debootstrap --variant=minbase bookworm "$rootfs" "$mirror"
  tar -C "$rootfs" -c . | podman import --change 'CMD ["bash"]' - "$BASE_IMAGE"
  rm -rf "$rootfs"
}

build_images() {
  local bud=(buildah bud --isolation chroot --pull=never --layers --force-rm -f "$SOURCE_DIR/Dockerfile")
  # The build stage gets a name of its own so that its layers are in use, not dangling, when
  # prune_stale_build_layers runs; the second command finds that stage in the layer cache.
  "${bud[@]}" --target build -t "$BUILD_STAGE_IMAGE" "$SOURCE_DIR"
  "${bud[@]}" -t "$IMAGE" "$SOURCE_DIR"
}

# Every source change leaves the previous build stage behind as untagged layers (over 1 GB).
# Remove dangling (untagged, childless) images from this Dockerfile's build stage, repeatedly,
# as removing a leaf can make its parent one; the cached package layer and the current build
# stage have children or a name, and stay.
prune_stale_build_layers() {
  local id removed=1
  while [[ $removed -eq 1 ]]; do
    removed=0
    for id in $(podman images --all --quiet --no-trunc --filter dangling=true); do
      if podman image inspect --format '{{range .History}}{{.CreatedBy}}{{"\n"}}{{end}}' "$id" |
          grep -q 'bash setup.sh deps'; then
        echo "removing stale build layer $id"
        # A build killed midway leaves a working container on its layer: the layer stays
        # (housekeeping, not the test's subject) rather than failing the run.
        if podman rmi "$id"; then
          removed=1
        else
          echo "kept $id: in use"
        fi
      fi
    done
  done
}

check_image_config() {
  local entrypoint user
  entrypoint="$(buildah inspect --type image --format '{{.OCIv1.Config.Entrypoint}}' "$IMAGE")"
  user="$(buildah inspect --type image --format '{{.OCIv1.Config.User}}' "$IMAGE")"
  echo "entrypoint: $entrypoint, user: $user"
  # Go's rendering of the list ["discreel"].
  [[ $entrypoint == '[discreel]' ]] || fail "image entrypoint is $entrypoint, expected [discreel]"
  [[ -n $user && $user != root && $user != 0 && $user != 0:* ]] || fail "image runs as root (user '$user')"
}

render_in_container() {
  buildah from --pull=never --name "$CONTAINER" "$IMAGE"
  # buildah run does not apply the entrypoint; it runs as the image's user. The output
  # directory must be writable by that (non-root) user, as a host directory is under `docker
  # run -u`.
  local uid
  uid="$(buildah run --isolation chroot "$CONTAINER" -- id -u)"
  echo "runs as uid $uid"
  [[ $uid != 0 ]] || fail "the container runs as root"
  buildah run --isolation chroot --volume "$WORK_DIR/container-out:/out" "$CONTAINER" -- \
    discreel render -o /out/demo.mp4
  [[ -s $WORK_DIR/container-out/demo.mp4 ]] || fail "the container wrote no /out/demo.mp4"
}

render_on_host() {
  "$HOST_DISCREEL" render -o "$WORK_DIR/host-out/demo.mp4"
  [[ -s $WORK_DIR/host-out/demo.mp4 ]] || fail "the host build wrote no demo.mp4"
}

# The image's service on loopback: started as the image's user with a volume for /data, checked
# with the image's own HEALTHCHECK command, sent a scene over HTTP, stopped by pid.
serve_in_container() {
  local out="$WORK_DIR/serve-stdout.txt" port="" server_pid discreel_pid id status="" check
  rm -rf "$WORK_DIR/serve-data" && mkdir -p "$WORK_DIR/serve-data" && chmod 0777 "$WORK_DIR/serve-data"
  buildah run --isolation chroot --volume "$WORK_DIR/serve-data:/data" "$CONTAINER" -- \
    discreel serve --listen 127.0.0.1:0 --data /data >"$out" 2>"$WORK_DIR/serve-log.jsonl" &
  server_pid=$!
  for _ in $(seq 100); do
    port="$(sed -n 's|^listening on http://127.0.0.1:\([0-9]*\)$|\1|p' "$out")"
    [[ -n $port ]] && break
    sleep 0.2
  done
  [[ -n $port ]] || fail "the service in the container did not start"
  echo "service on port $port"
  # The HEALTHCHECK line of the Dockerfile, unescaped from JSON, on this port.
  check="$(grep -o "exec 3<>/dev/tcp[^\"]*" "$SOURCE_DIR/Dockerfile" | sed 's/\\\\/\\/g; s/8080/'"$port"'/')"
  buildah run --isolation chroot "$CONTAINER" -- bash -c "$check" || fail "the image's health check failed"
  local scene='version: 1\nvideo:\n  size: [320, 180]\ndiscs:\n  - position: [0, 0]\n    radius: 0.4\n'
  printf "$scene" >"$WORK_DIR/serve-scene.yaml"
  id="$(curl -sf -X POST -H 'Content-Type: application/json' --data "{\"scene\": \"$scene\", \"output\": \"png\"}" \
    "http://127.0.0.1:$port/v1/renders" | sed -n 's/.*"id":"\([0-9a-f]*\)".*/\1/p')"
  [[ -n $id ]] || fail "the service did not accept the scene"
  for _ in $(seq 120); do
    status="$(curl -sf "http://127.0.0.1:$port/v1/renders/$id" | sed -n 's/.*"status":"\([a-z]*\)".*/\1/p')"
    [[ $status == succeeded || $status == failed ]] && break
    sleep 0.5
  done
  [[ $status == succeeded ]] || fail "the job ended '$status'"
  curl -sf -o "$WORK_DIR/container-out/served.png" "http://127.0.0.1:$port/v1/renders/$id/output"
  discreel_pid="$(pgrep -f -- "discreel serve --listen 127.0.0.1:0 --data /data" | head -n 1)"
  [[ -n $discreel_pid ]] && kill -TERM "$discreel_pid"
  wait "$server_pid" || true
  "$HOST_DISCREEL" render "$WORK_DIR/serve-scene.yaml" -o "$WORK_DIR/host-out/served.png" -q
  [[ "$(stream_facts "$WORK_DIR/container-out/served.png")" == "$(stream_facts "$WORK_DIR/host-out/served.png")" ]] ||
    fail "the still the service rendered differs from the host's"
  echo "rendered $id through the service: $(stat -c %s "$WORK_DIR/container-out/served.png") bytes"
}

# The image as a Kubernetes Indexed Job runs it (deploy/k8s/batch-job.yaml): `batch` with
# JOB_COMPLETION_INDEX in the environment renders that line of the manifest.
batch_in_container() {
  local dir="$WORK_DIR/container-batch"
  rm -rf "$dir" && mkdir -p "$dir" && chmod 0777 "$dir"
  printf 'version: 1\nvideo:\n  size: [64, 36]\ndiscs:\n  - position: [0, 0]\n    radius: 0.4\n' >"$dir/s.yaml"
  printf '# two stills\ns.yaml -o first.png\ns.yaml -o second.png --size 32x18\n' >"$dir/renders.txt"
  buildah run --isolation chroot --env JOB_COMPLETION_INDEX=1 --volume "$dir:/work" \
    --workingdir /work "$CONTAINER" -- discreel batch /work/renders.txt
  [[ -s $dir/second.png && ! -e $dir/first.png ]] || fail "index 1 did not render second.png alone"
  [[ "$(stream_facts "$dir/second.png")" == *width=32* ]] || fail "second.png is not 32 wide"
  # deploy/k8s/clip-*-job.yaml: each index renders its segment, then concat joins them into the
  # bytes of one render.
  printf 'version: 1\nvideo:\n  size: [64, 36]\n  duration: 1\n  segment: 0.5\ndiscs:\n  - position: [0, 0]\n    velocity: [1, 0]\n    radius: 0.4\n' >"$dir/clip.yaml"
  local index
  for index in 0 1; do
    buildah run --isolation chroot --env JOB_COMPLETION_INDEX=$index --volume "$dir:/work" \
      --workingdir /work "$CONTAINER" -- bash -c \
      'exec discreel render clip.yaml -o clip.segments --segment "$JOB_COMPLETION_INDEX" --format mp4'
  done
  buildah run --isolation chroot --volume "$dir:/work" --workingdir /work "$CONTAINER" -- \
    discreel concat clip.segments -o clip.mp4
  buildah run --isolation chroot --volume "$dir:/work" --workingdir /work "$CONTAINER" -- \
    discreel render clip.yaml -o whole.mp4
  cmp "$dir/clip.mp4" "$dir/whole.mp4" || fail "the joined segments differ from one render"
}

remove_container() {
  buildah rm "$CONTAINER" >/dev/null 2>&1 || true
}

stream_facts() {
  ffprobe -v error -select_streams v:0 -count_frames \
    -show_entries stream=codec_name,pix_fmt,width,height,r_frame_rate,nb_read_frames \
    -of default=noprint_wrappers=1 "$1"
}

compare_clips() {
  local container_facts host_facts
  container_facts="$(stream_facts "$WORK_DIR/container-out/demo.mp4")"
  host_facts="$(stream_facts "$WORK_DIR/host-out/demo.mp4")"
  echo "container clip:"; echo "$container_facts"
  echo "host clip:"; echo "$host_facts"
  grep -qx 'codec_name=h264' <<<"$container_facts" || fail "the container's clip is not H.264"
  grep -Eqx 'nb_read_frames=[1-9][0-9]*' <<<"$container_facts" || fail "the container's clip has no frames"
  [[ $container_facts == "$host_facts" ]] || fail "the container's clip differs from the host's"
}

[[ $EUID -eq 0 ]] || fail "needs root (buildah with chroot isolation); skip it with: ctest -LE container"
for tool in buildah podman debootstrap ffprobe curl; do
  command -v "$tool" >/dev/null ||
    fail "$tool is missing: run 'bash setup.sh test' to install it, or skip this test with: ctest -LE container"
done
[[ -x $HOST_DISCREEL ]] || fail "no host binary at $HOST_DISCREEL"

total_start=$SECONDS
mkdir -p "$WORK_DIR"
# One container test at a time per machine: they share the image store, and one run's prune
# would remove another's layers mid-build.
readonly LOCK=/var/tmp/discreel-container-test.lock
exec 9>"$LOCK"
if ! flock --nonblock 9; then
  echo "waiting for another container test to finish (lock: $LOCK)"
  flock 9
fi
rm -rf "$WORK_DIR/container-out" "$WORK_DIR/host-out"
mkdir -p "$WORK_DIR/container-out" "$WORK_DIR/host-out"
chmod 0777 "$WORK_DIR/container-out"
echo "logs in $WORK_DIR"

if podman image exists "$BASE_IMAGE"; then
  echo "[base-image] reusing $BASE_IMAGE from local storage"
else
  step base-image make_base_image
fi
step image build_images
step prune prune_stale_build_layers
step image-config check_image_config
trap remove_container EXIT
step container-render render_in_container
step host-render render_on_host
step compare compare_clips
step container-serve serve_in_container
step container-batch batch_in_container
echo "container test passed in $((SECONDS - total_start)) s"
