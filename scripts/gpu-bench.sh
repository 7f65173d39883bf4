#!/usr/bin/env bash
# The benchmarks of docs/benchmarks.md, in one run on a machine with a GPU,
# headless through EGL: strata-bench on the seeded scenes and on real models,
# and strata-render's whole-process time to first image on each model.
#
#   scripts/gpu-bench.sh [--bundle DIR] [--out DIR] [--quick] [--budget S]
#                        [--frames N] [--warmup N] [--runs N] [--models DIR]
#                        [--parts synthetic,files,first-image,opencsg,export]
#                        [--export-models FILE,...] [--export-resolutions N,...]
#                        [--look strata|openscad]
#
# Binaries: with --bundle, DIR/bin/strata-bench and strata-render run on
# DIR/lib and DIR/fonts (scripts/gpu-bundle.py makes such a folder, for a
# machine without Debian's packages; only the two binaries get that
# environment, not python3 or nvidia-smi); without it, scripts/build.sh
# release builds them here. Models: examples/*.csg and, with a bundle,
# DIR/models/*.csg (--models DIR names another folder). Where NVIDIA's driver
# sits outside glvnd's folders (/usr/local/nvidia in a container), its EGL
# vendor file and libraries are found there.
#
# What it runs, in this order, each step under `timeout`; a step that fails
# is logged and the next one runs. strata-bench's figures are medians of
# --frames (default 50) after --warmup (default 10) frames; a GPU is first
# kept busy for a few seconds, so that it leaves its idle clocks.
#   probe        one small frame: the GL renderer, and where each library the
#                process loads comes from
#   synthetic    strata-bench --no-opencsg: cheese K = 1..1024 at 1024x768;
#                stack, intersection, deep, tori, mesh K = 1..256 at 512x512;
#                cheese again at 1920x1080. One process per scene and size;
#                where one dies without its JSON, its K are rerun one by one.
#   files        strata-bench --no-opencsg --files, one process per model,
#                1024x768.
#   first-image  strata-render MODEL -o x.png --imgsize 1024,768 --stats as a
#                whole process, --runs times (default 3): the median wall
#                time, the first run's (a shader cache of its own, empty, for
#                each model: NVIDIA's and Mesa's on-disk caches would
#                otherwise hold the shaders of earlier runs), peak RSS where
#                GNU time is installed, and the --stats figures.
#   opencsg      strata-bench with OpenCSG (as OpenSCAD's preview draws the
#                tree) through an EGL compatibility context, no display
#                needed: cheese K = 64 and 256 at 1024x768 and 1920x1080,
#                and each model at 1024x768; 10 frames after 3, every OpenCSG
#                setting capped at 2 s a frame.
#   export       strata-render MODEL --export x.stl --export-sampled --export-resolution N
#                --stats, once per model (--export-models, default
#                examples/*.csg) and resolution (--export-resolutions,
#                default 512): the whole process's wall time, peak RSS, the
#                export's own milliseconds (sampling and contouring apart)
#                and the triangles written. Not in
#                the default --parts.
# --look openscad: strata-bench draws as OpenSCAD's preview looks (its light,
# no outline: --light openscad --no-outline), as OpenCSG is drawn; default
# strata's own look.
# --budget S (default 330) bounds the whole: a step gets at most the time
# left, and steps that no longer fit are skipped and listed, so the run
# ends within about six minutes. --quick: small images, K = 1 and 8,
# 2 frames, 2 runs; a check of the script itself on llvmpipe in about a
# minute.
#
# Writes to --out DIR (default ./gpu-bench-out), eight files at most:
#   log.txt               everything the steps print, with times
#   env.json              GPU (nvidia-smi), GL renderer, CPU, OS, commit, where
#                         each loaded library came from
#   bench-synthetic.json  strata-bench --json of the synthetic steps, merged
#   bench-files.json      the same for the models
#   bench-opencsg.json    the same, with OpenCSG beside strata
#   first-image.json      every run of strata-render, with its --stats
#   export.json           every export run, with its --stats
#   images.tar            the first-image PNGs, to check what the GPU drew
#   report.md             the tables: scripts/bench-report.py (where python3
#                         is installed) and per-pass and first-image tables
set -uo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
[[ -f $root/scripts/bench-report.py ]] || root=$(pwd)
bundle="" out=./gpu-bench-out quick=0 budget=330 frames="" warmup="" runs="" models="" parts=synthetic,files,first-image,opencsg
export_models="" export_resolutions=512 look=strata
while (($#)); do
  case $1 in
    --bundle) bundle=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --quick) quick=1; shift ;;
    --budget) budget=$2; shift 2 ;;
    --frames) frames=$2; shift 2 ;;
    --warmup) warmup=$2; shift 2 ;;
    --runs) runs=$2; shift 2 ;;
    --models) models=$2; shift 2 ;;
    --parts) parts=$2; shift 2 ;;
    --export-models) export_models=$2; shift 2 ;;
    --export-resolutions) export_resolutions=$2; shift 2 ;;
    --look) look=$2; shift 2 ;;
    -h|--help) sed -n '2,/^set -uo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) echo "gpu-bench: unknown option $1 (--help)" >&2; exit 2 ;;
  esac
done
mkdir -p "$out" || exit 1
out=$(cd "$out" && pwd)
[[ -n $bundle ]] && { bundle=$(cd "$bundle" && pwd) || exit 1; }
[[ -z $models && -n $bundle && -d $bundle/models ]] && models=$bundle/models
[[ -n $models ]] && { models=$(cd "$models" && pwd) || exit 1; }
cd "$root" || exit 1

exec > >(tee -a "$out/log.txt") 2>&1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
start=$EPOCHREALTIME
deadline=$(awk -v s="$start" -v b="$budget" 'BEGIN {printf "%d", s + b}')
log() { printf '[%6.1f s] %s\n' "$(awk -v s="$start" -v n="$EPOCHREALTIME" 'BEGIN {print n - s}')" "$*"; }
left() { awk -v d="$deadline" -v n="$EPOCHREALTIME" 'BEGIN {printf "%d", d - n}'; }
failures=()
fail() { failures+=("$*"); log "FAILED: $*"; }
skipped=()

# ---- what runs, and how many frames --------------------------------------
if ((quick)); then
  : "${frames:=2}" "${warmup:=1}" "${runs:=2}"
  syn=("cheese 1,8 160x120" "stack 1,8 128x128" "intersection 1,8 128x128" "deep 1,8 128x128"
       "tori 1,8 128x128" "mesh 1,8 128x128" "cheese 8 200x150")
  file_size=160x120 img_size=160,120 step_limit=60
else
  : "${frames:=50}" "${warmup:=10}" "${runs:=3}"
  syn=("cheese 1,8,32,64,128,256,1024 1024x768")
  for s in stack intersection deep tori mesh; do syn+=("$s 1,8,32,64,256 512x512"); done
  syn+=("cheese 1,8,32,64,128,256,1024 1920x1080")
  file_size=1024x768 img_size=1024,768 step_limit=120
fi
has_part() { [[ ,$parts, == *,$1,* ]]; }

# ---- binaries and their environment ----------------------------------------
runenv=()
if [[ -n $bundle ]]; then
  bench=$bundle/bin/strata-bench render=$bundle/bin/strata-render
  runenv+=("LD_LIBRARY_PATH=$bundle/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}")
  if [[ -f $bundle/fonts/fonts.conf ]]; then
    runenv+=("FONTCONFIG_FILE=$bundle/fonts/fonts.conf" "OPENSCAD_FONT_PATH=$bundle/fonts")
  fi
  commit=$(cat "$bundle/bin/COMMIT" 2>/dev/null || echo unknown)
else
  log "building Release (scripts/build.sh release)"
  scripts/build.sh release || { log "build failed; install the dependencies (scripts/deps.sh) or use --bundle"; exit 1; }
  bench=build/apps/strata-bench/strata-bench render=build/apps/strata-render/strata-render
  commit=$(git rev-parse HEAD 2>/dev/null || echo unknown)
fi
[[ -f $bench && -f $render ]] || { log "no strata-bench/strata-render at $bench, $render"; exit 1; }
if [[ ! -x $bench || ! -x $render ]]; then   # a copy that lost the modes
  chmod +x "$bench" "$render" 2>/dev/null ||
    { cp "$bench" "$render" "$work/" && chmod +x "$work"/strata-* &&
      bench=$work/strata-bench render=$work/strata-render; }
fi

# NVIDIA's driver outside the usual places (a container's /usr/local/nvidia):
# point glvnd at its EGL vendor file and the loader at its libraries.
smi=$(command -v nvidia-smi || ls /usr/local/nvidia/bin/nvidia-smi 2>/dev/null || true)
if [[ -n $smi ]]; then
  if [[ -z ${__EGL_VENDOR_LIBRARY_FILENAMES:-} && -z ${__EGL_VENDOR_LIBRARY_DIRS:-} ]] &&
     ! ls /usr/share/glvnd/egl_vendor.d/*nvidia*.json /etc/glvnd/egl_vendor.d/*nvidia*.json >/dev/null 2>&1; then
    for j in /usr/local/nvidia/share/glvnd/egl_vendor.d/*nvidia*.json /usr/local/share/glvnd/egl_vendor.d/*nvidia*.json; do
      [[ -f $j ]] && { export __EGL_VENDOR_LIBRARY_FILENAMES=$j; break; }
    done
  fi
  if ! ldconfig -p 2>/dev/null | grep -q libEGL_nvidia; then
    for d in /usr/local/nvidia/lib64 /usr/local/nvidia/lib; do
      if [[ -e $d/libEGL_nvidia.so.0 && :${LD_LIBRARY_PATH:-}: != *:$d:* ]]; then
        if ((${#runenv[@]})); then runenv[0]+=":$d"; else runenv+=("LD_LIBRARY_PATH=$d${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"); fi
        break
      fi
    done
  fi
fi
sx() { env "${runenv[@]}" "$@"; }   # the binaries' environment, for them only

# timeout for a step: its limit, or the time left, whichever is less; 0 when
# too little is left to start it
step_time() {
  local l; l=$(left)
  ((l < 5)) && { echo 0; return; }
  ((l < $1)) && echo "$l" || echo "$1"
}

log "strata $commit; bench $bench; out $out; budget ${budget} s; frames $frames, warm-up $warmup"
log "EGL vendor file: ${__EGL_VENDOR_LIBRARY_FILENAMES:-the glvnd default}; environment of the binaries: ${runenv[*]:-none}"

# ---- the machine ------------------------------------------------------------
gpu_before="" gpu_after="" smi_list="" smi_full=""
gpu_query="name,driver_version,memory.total,pstate,clocks.sm,clocks.mem,clocks.max.sm,temperature.gpu,power.draw"
if [[ -n $smi ]]; then
  smi_list=$(timeout 30 "$smi" -L 2>&1)
  smi_full=$(timeout 30 "$smi" 2>&1)
  gpu_before=$(timeout 30 "$smi" --query-gpu=$gpu_query --format=csv 2>&1)
  printf '%s\n%s\n' "$smi_list" "$gpu_before"
else
  log "no nvidia-smi: not an NVIDIA machine, or its tools are elsewhere"
fi
cpu=$(grep -m1 'model name' /proc/cpuinfo 2>/dev/null | sed 's/.*: //')
os=$( (. /etc/os-release 2>/dev/null && echo "$PRETTY_NAME") || uname -s)
glibc=$(getconf GNU_LIBC_VERSION 2>/dev/null | sed 's/^glibc //')

# One small frame: the GL renderer, and where every library it loads is
# found (with a bundle: its lib/, or the system's for glibc and GL).
log "probe: strata-bench, one small frame"
probe_out=$(timeout 60 env "${runenv[@]}" LD_DEBUG=libs LD_DEBUG_OUTPUT="$work/ld" \
  "$bench" --no-opencsg --scenes cheese --k 1 --size 64x64 --frames 1 --warmup 0 2>&1)
probe_rc=$?
echo "$probe_out" | head -5
renderer=$(echo "$probe_out" | sed -n 's/^# \(.*\); median of.*/\1/p' | head -1)
[[ $probe_rc -eq 0 && -n $renderer ]] || fail "probe (strata-bench exit $probe_rc): no GL context?"
log "GL renderer: ${renderer:-unknown}"
libs=$(cat "$work"/ld.* 2>/dev/null | sed -n 's/.*calling init: //p' | sort -u)
libs_outside=$(echo "$libs" | grep -v "^${bundle:-/nonexistent}/lib/" | grep -v '^$')
log "libraries from outside the bundle: $(echo "$libs_outside" | xargs -n1 basename 2>/dev/null | tr '\n' ' ')"

# ---- JSON helpers -----------------------------------------------------------
jstr() {
  local s=$1
  s=${s//\\/\\\\}; s=${s//\"/\\\"}; s=${s//$'\t'/\\t}; s=${s//$'\r'/}; s=${s//$'\n'/\\n}
  printf '"%s"' "$s"
}
# strata-bench --json files into one, their "results" joined (its writer puts
# "results" last, one key per line)
merge_bench_json() {
  local dest=$1; shift
  (($#)) || { rm -f "$dest"; return; }
  awk '
    FNR == 1 { f++; state = 0 }
    state == 0 {
      if (f == 1) hdr[++h] = $0
      if ($0 ~ /^  "results": \[/) state = ($0 ~ /\]/) ? 2 : 1
      next
    }
    state == 1 && /^  \]/ { state = 2; next }
    state == 1 { if (!started[f]++ && n > 0) body[n] = body[n] ","; body[++n] = $0 }
    END {
      for (i = 1; i < h; i++) print hdr[i]
      print "  \"results\": ["
      for (i = 1; i <= n; i++) print body[i]
      print "  ]"
      print "}"
    }' "$@" >"$dest"
}
# per-pass table of a merged file, without python
passes_table() {
  awk '
    function flush() { if (scene != "") printf "| %s | %s | %sx%s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", scene, k, w, hh, v["strata_ms"], v["plain_ms"], v["peel_ms"], v["evaluate_ms"], v["normal_ms"], v["shade_ms"], v["setup_ms"], v["texture_mib"], v["error"]; scene = ""; delete v }
    BEGIN { print "| scene | K | size | strata ms | plain ms | peel ms | eval ms | normal ms | shade ms | setup ms | texture MiB | error |"
            print "| --- | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |" }
    /^    {$/ { flush(); inres = 1; next }
    !inres { next }
    /^      "[a-z_]+": / {
      key = $1; gsub(/[":]/, "", key); val = $0; sub(/^[^:]*: /, "", val); sub(/,$/, "", val); gsub(/"/, "", val)
      if (key == "scene") scene = val; else if (key == "k") k = val; else if (key == "width") w = val
      else if (key == "height") hh = val
      else if (key == "texture_bytes") v["texture_mib"] = sprintf("%.1f", val / 1048576)
      else if (key ~ /_ms$/) v[key] = (val + 0 >= 100) ? sprintf("%.0f", val) : (val + 0 >= 10) ? sprintf("%.1f", val) : sprintf("%.2f", val)
      else if (key == "error") v["error"] = val
    }
    END { flush() }' "$1"
}

# ---- synthetic scenes -------------------------------------------------------
# A GPU idles at low clocks: a few seconds of frames first, discarded.
if ((!quick)) && has_part synthetic; then
  log "warm-up: strata-bench cheese K=64 1024x768, 200 frames or 15 s, not recorded"
  timeout -k 5 15 env "${runenv[@]}" "$bench" --no-opencsg --scenes cheese --k 64 --size 1024x768 \
    --frames 200 --warmup 0 2>&1 | grep '^cheese'
fi

opencsg_args=(--no-opencsg)   # the opencsg part sets its own
look_args=()
case $look in
  strata) ;;
  openscad) look_args=(--light openscad --no-outline) ;;
  *) echo "gpu-bench: --look strata or openscad, not $look" >&2; exit 2 ;;
esac
run_bench() {   # name json timeout args... ; 0 when the JSON was written
  local name=$1 json=$2 t=$3; shift 3
  log "strata-bench $name ($*) [timeout ${t} s]"
  timeout -k 5 "$t" env "${runenv[@]}" "$bench" "${opencsg_args[@]}" ${look_args[@]+"${look_args[@]}"} \
    --frames "$frames" --warmup "$warmup" --json "$json" "$@" 2>&1 | grep -v '^    opencsg: OpenCSG left out'
  local rc=${PIPESTATUS[0]}
  if [[ ! -s $json ]]; then fail "strata-bench $name: exit $rc, no JSON$( ((rc == 124 || rc == 137)) && echo ' (timed out)')"; return 1; fi
  ((rc == 0)) || fail "strata-bench $name: exit $rc (a case failed; its row says why)"
  return 0
}
syn_json=()
if has_part synthetic; then
  i=0
  for entry in "${syn[@]}"; do
    read -r scene ks size <<<"$entry"
    i=$((i + 1))
    t=$(step_time "$step_limit")
    if ((t == 0)); then skipped+=("synthetic $scene $size"); continue; fi
    if run_bench "$scene $size" "$work/syn-$i.json" "$t" --scenes "$scene" --k "$ks" --size "$size"; then
      syn_json+=("$work/syn-$i.json")
    elif [[ $ks == *,* ]]; then
      log "rerunning $scene $size one K at a time"
      for k in ${ks//,/ }; do
        t=$(step_time $((step_limit / 2)))
        if ((t == 0)); then skipped+=("synthetic $scene $size K=$k"); continue; fi
        run_bench "$scene K=$k $size" "$work/syn-$i-$k.json" "$t" --scenes "$scene" --k "$k" --size "$size" &&
          syn_json+=("$work/syn-$i-$k.json")
      done
    fi
    merge_bench_json "$out/bench-synthetic.json" "${syn_json[@]}"
  done
fi

# ---- real models ------------------------------------------------------------
files=(examples/*.csg)
[[ -n $models ]] && files+=("$models"/*.csg)
files_json=()
if has_part files; then
  i=0
  for f in "${files[@]}"; do
    i=$((i + 1))
    t=$(step_time 60)
    if ((t == 0)); then skipped+=("files $(basename "$f")"); continue; fi
    run_bench "$(basename "$f")" "$work/file-$i.json" "$t" --files "$f" --size "$file_size" &&
      files_json+=("$work/file-$i.json")
    merge_bench_json "$out/bench-files.json" "${files_json[@]}"
  done
fi

# ---- time to first image ----------------------------------------------------
# a number of a strata-render --stats object (its time_ms are indented by 4)
fstat() { echo "$1" | sed -n "s/^    \"$2\": \([0-9.e+-]*\).*/\1/p" | head -1; }
ms() { [[ -n $1 ]] && awk -v x="$1" 'BEGIN {printf "%.0f", x}' || echo "–"; }
first_rows=()
if has_part first-image; then
  gnutime=$(command -v /usr/bin/time || true)
  [[ -n $gnutime ]] || log "no /usr/bin/time: first-image without peak RSS"
  mkdir -p "$work/img"
  models_json=()
  for f in "${files[@]}"; do
    n=$(basename "$f" .csg)
    walls=() rsss=() rcs=() stats_first="null" stats_last="null"
    cache="$work/shader-cache-$n"
    for ((r = 1; r <= runs; r++)); do
      t=$(step_time 60)
      if ((t == 0)); then skipped+=("first-image $n run $r"); break; fi
      rm -f "$work/stats.json" "$work/t"
      s=$EPOCHREALTIME
      if [[ -n $gnutime ]]; then
        timeout -k 5 "$t" "$gnutime" -f "%M" -o "$work/t" env "${runenv[@]}" \
          __GL_SHADER_DISK_CACHE_PATH="$cache" MESA_SHADER_CACHE_DIR="$cache" \
          "$render" "$f" -o "$work/img/$n.png" --imgsize "$img_size" --stats >"$work/stats.json" 2>"$work/err"
      else
        timeout -k 5 "$t" env "${runenv[@]}" __GL_SHADER_DISK_CACHE_PATH="$cache" MESA_SHADER_CACHE_DIR="$cache" \
          "$render" "$f" -o "$work/img/$n.png" --imgsize "$img_size" --stats >"$work/stats.json" 2>"$work/err"
      fi
      rc=$?
      e=$EPOCHREALTIME
      rcs+=("$rc")
      if ((rc != 0)); then
        fail "strata-render $n run $r: exit $rc: $(grep -v 'meshing\|exact ' "$work/err" | tail -2 | tr '\n' ' ')"
        continue
      fi
      walls+=("$(awk -v s="$s" -v e="$e" 'BEGIN {printf "%.4f", e - s}')")
      [[ -n $gnutime && -s $work/t ]] && rsss+=("$(tail -1 "$work/t")")
      [[ $r -eq 1 ]] && stats_first=$(cat "$work/stats.json")
      stats_last=$(cat "$work/stats.json")
    done
    ((${#walls[@]})) || continue
    median=$(printf '%s\n' "${walls[@]}" | sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}')
    rss_med=""
    ((${#rsss[@]})) && rss_med=$(printf '%s\n' "${rsss[@]}" | sort -g | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}')
    log "first image $n: wall ${walls[*]} s${rss_med:+, peak RSS $rss_med KiB}"
    first_rows+=("$(printf '| `%s` | %.3f | %.3f | %s | %s | %s | %s | %s |' "$n.csg" "$median" "${walls[0]}" \
      "$([[ -n $rss_med ]] && awk -v k="$rss_med" 'BEGIN {printf "%.0f", k / 1024}' || echo –)" \
      "$(ms "$(fstat "$stats_last" total)")" "$(ms "$(fstat "$stats_last" context)")" \
      "$(ms "$(fstat "$stats_last" geometry)")" "$(ms "$(fstat "$stats_last" frame)")")")
    models_json+=("$(printf '{"model": %s, "wall_s": [%s], "median_s": %s, "first_s": %s, "max_rss_kib": [%s], "exit": [%s],\n   "stats_first": %s,\n   "stats_last": %s}' \
      "$(jstr "$f")" "$(IFS=,; echo "${walls[*]}")" "$median" "${walls[0]}" "$(IFS=,; echo "${rsss[*]:-}")" \
      "$(IFS=,; echo "${rcs[*]}")" "$stats_first" "$stats_last")")
  done
  {
    printf '{"tool": "gpu-bench first-image", "renderer": %s, "imgsize": %s, "runs": %s, "gnu_time": %s,\n "models": [\n  ' \
      "$(jstr "$renderer")" "$(jstr "$img_size")" "$runs" "$([[ -n $gnutime ]] && echo true || echo false)"
    sep=""
    for m in "${models_json[@]}"; do printf '%s%s' "$sep" "$m"; sep=$',\n  '; done
    printf '\n ]\n}\n'
  } >"$out/first-image.json"
  (cd "$work/img" && ls ./*.png >/dev/null 2>&1 && tar -cf "$out/images.tar" ./*.png)
fi

# ---- OpenCSG beside strata ----------------------------------------------------
# OpenSCAD's preview on the same GPU: the comparator's own compatibility
# context through EGL (strata-bench --opencsg-context egl), fewer frames, as
# OpenCSG's slower settings take seconds a frame on the large scenes.
opencsg_json=()
if has_part opencsg; then
  opencsg_args=(--opencsg-context egl --opencsg-cap-ms 2000)
  saved_frames=$frames saved_warmup=$warmup
  ((quick)) || { frames=10 warmup=3; }
  cases=("--scenes cheese --k 64,256 --size $file_size")
  ((quick)) || cases+=("--scenes cheese --k 64,256 --size 1920x1080")
  for f in "${files[@]}"; do cases+=("--files $f --size $file_size"); done
  i=0
  for c in "${cases[@]}"; do
    i=$((i + 1))
    t=$(step_time "$step_limit")
    if ((t == 0)); then skipped+=("opencsg $c"); continue; fi
    # shellcheck disable=SC2086  # the case's words are options
    run_bench "OpenCSG $i" "$work/opencsg-$i.json" "$t" $c && opencsg_json+=("$work/opencsg-$i.json")
    merge_bench_json "$out/bench-opencsg.json" "${opencsg_json[@]}"
  done
  frames=$saved_frames warmup=$saved_warmup
  opencsg_args=(--no-opencsg)
fi

# ---- export -------------------------------------------------------------------
export_rows=()
if has_part export; then
  gnutime=$(command -v /usr/bin/time || true)
  if [[ -n $export_models ]]; then IFS=, read -r -a emodels <<<"$export_models"; else emodels=(examples/*.csg); fi
  IFS=, read -r -a eres <<<"$export_resolutions"
  exports_json=()
  for f in "${emodels[@]}"; do
    n=$(basename "$f" .csg)
    for res in "${eres[@]}"; do
      t=$(step_time 120)
      if ((t == 0)); then skipped+=("export $n $res"); continue; fi
      rm -f "$work/stats.json" "$work/t" "$work/x.stl"
      s=$EPOCHREALTIME
      if [[ -n $gnutime ]]; then
        timeout -k 5 "$t" "$gnutime" -f "%M" -o "$work/t" env "${runenv[@]}" \
          "$render" "$f" --export "$work/x.stl" --export-sampled --export-resolution "$res" --stats >"$work/stats.json" 2>"$work/err"
      else
        timeout -k 5 "$t" env "${runenv[@]}" \
          "$render" "$f" --export "$work/x.stl" --export-sampled --export-resolution "$res" --stats >"$work/stats.json" 2>"$work/err"
      fi
      rc=$?
      e=$EPOCHREALTIME
      if ((rc != 0)); then
        fail "export $n at $res: exit $rc: $(grep -v 'contour\|sampling\|meshing' "$work/err" | tail -2 | tr '\n' ' ')"
        continue
      fi
      wall=$(awk -v s="$s" -v e="$e" 'BEGIN {printf "%.3f", e - s}')
      rss=""; [[ -n $gnutime && -s $work/t ]] && rss=$(tail -1 "$work/t")
      tris=$(od -An -tu4 -j80 -N4 "$work/x.stl" 2>/dev/null | tr -d ' ')  # binary STL: the count after the header
      st=$(cat "$work/stats.json")
      log "export $n at $res: $wall s, ${tris:-?} triangles${rss:+, peak RSS $rss KiB}"
      export_rows+=("$(printf '| `%s` | %s | %.2f | %s | %s | %s | %s | %s |' "$n.csg" "$res" "$wall" \
        "$(ms "$(fstat "$st" export)")" "$(ms "$(fstat "$st" export_sample)")" "$(ms "$(fstat "$st" export_contour)")" \
        "$([[ -n $rss ]] && awk -v k="$rss" 'BEGIN {printf "%.0f", k / 1024}' || echo –)" \
        "${tris:-–}")")
      exports_json+=("$(printf '{"model": %s, "resolution": %s, "wall_s": %s, "max_rss_kib": %s, "triangles": %s,\n   "stats": %s}' \
        "$(jstr "$f")" "$res" "$wall" "${rss:-null}" "${tris:-null}" "$st")")
    done
  done
  {
    printf '{"tool": "gpu-bench export", "renderer": %s,\n "exports": [\n  ' "$(jstr "$renderer")"
    sep=""
    for m in "${exports_json[@]}"; do printf '%s%s' "$sep" "$m"; sep=$',\n  '; done
    printf '\n ]\n}\n'
  } >"$out/export.json"
fi

# ---- the machine, after -------------------------------------------------------
[[ -n $smi ]] && gpu_after=$(timeout 30 "$smi" --query-gpu=$gpu_query --format=csv 2>&1)
{
  printf '{\n'
  printf '  "date": %s,\n' "$(jstr "$(date -u +%Y-%m-%dT%H:%M:%SZ)")"
  printf '  "commit": %s,\n' "$(jstr "$commit")"
  printf '  "renderer": %s,\n' "$(jstr "$renderer")"
  printf '  "nvidia_smi_L": %s,\n' "$(jstr "$smi_list")"
  printf '  "gpu_before": %s,\n' "$(jstr "$gpu_before")"
  printf '  "gpu_after": %s,\n' "$(jstr "$gpu_after")"
  printf '  "nvidia_smi": %s,\n' "$(jstr "$smi_full")"
  printf '  "egl_vendor_file": %s,\n' "$(jstr "${__EGL_VENDOR_LIBRARY_FILENAMES:-}")"
  printf '  "cpu": %s,\n  "cores": %s,\n' "$(jstr "$cpu")" "$(nproc)"
  printf '  "memory": %s,\n' "$(jstr "$(grep MemTotal /proc/meminfo 2>/dev/null)")"
  printf '  "os": %s,\n  "kernel": %s,\n  "glibc": %s,\n' "$(jstr "$os")" "$(jstr "$(uname -r)")" "$(jstr "$glibc")"
  printf '  "bundle": %s,\n' "$(jstr "$bundle")"
  printf '  "binaries_environment": %s,\n' "$(jstr "${runenv[*]:-}")"
  printf '  "libraries_outside_bundle": %s,\n' "$(jstr "$libs_outside")"
  printf '  "options": {"quick": %s, "frames": %s, "warmup": %s, "runs": %s, "budget_s": %s},\n' \
    "$quick" "$frames" "$warmup" "$runs" "$budget"
  printf '  "failures": %s,\n' "$(jstr "$(printf '%s\n' "${failures[@]:-}")")"
  printf '  "skipped": %s,\n' "$(jstr "$(printf '%s\n' "${skipped[@]:-}")")"
  printf '  "seconds": %s\n}\n' "$(awk -v s="$start" -v n="$EPOCHREALTIME" 'BEGIN {printf "%.1f", n - s}')"
} >"$out/env.json"

# ---- report -----------------------------------------------------------------
py=$(command -v python3 || true)
{
  gpu_name=$(echo "$smi_list" | head -1 | sed 's/ (UUID.*//; s/^GPU 0: //')
  echo "# strata's benchmarks on ${gpu_name:-${renderer:-an unknown GL}}"
  echo
  echo "- GL: ${renderer:-unknown}"
  echo "- strata $commit; $( [[ -n $bundle ]] && echo "bundle $bundle" || echo "built here")"
  echo "- CPU: $cpu, $(nproc) cores; $os; glibc $glibc"
  echo "- $frames frames after $warmup warm-up per case; first image: $runs runs; strata's frames in the $look look; $(date -u +%Y-%m-%d)"
  for part in synthetic files opencsg; do
    f="$out/bench-$part.json"
    [[ -s $f ]] || continue
    echo
    case $part in
      synthetic) echo "## strata-bench: the seeded scenes" ;;
      files) echo "## strata-bench: real models, $file_size" ;;
      opencsg) echo "## strata-bench against OpenCSG (EGL), 10 frames after 3" ;;
    esac
    echo
    if [[ -n $py ]]; then "$py" scripts/bench-report.py "$f" 2>&1; echo; fi
    echo "Per pass (medians):"
    echo
    passes_table "$f"
  done
  if ((${#first_rows[@]})); then
    echo
    echo "## Time to first image: strata-render, whole process, $img_size"
    echo
    echo "Wall seconds: median of $runs runs, and the first run's with an empty shader cache; in-process milliseconds from the last run's --stats."
    echo
    echo "| model | median s | first s | peak MiB | total ms | context ms | geometry ms | frame ms |"
    echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
    printf '%s\n' "${first_rows[@]}"
  fi
  if ((${#export_rows[@]})); then
    echo
    echo "## Export: strata-render --export, whole process"
    echo
    echo "| model | cells | wall s | export ms | sampling ms | contouring ms | peak MiB | triangles |"
    echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
    printf '%s\n' "${export_rows[@]}"
  fi
  echo
  echo "## Failures and skipped steps"
  echo
  ((${#failures[@]})) && printf -- '- %s\n' "${failures[@]}" || echo "- no failure"
  ((${#skipped[@]})) && printf -- '- skipped (out of time): %s\n' "${skipped[@]}"
} >"$out/report.md"

log "done: ${#failures[@]} failures, ${#skipped[@]} steps skipped; $(ls "$out" | tr '\n' ' ')"
((${#failures[@]} == 0))
