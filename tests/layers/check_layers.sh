#!/usr/bin/env bash
# Layer direction (../shared/DESIGN.md, "Layers"; issue 18): every #include "<folder>/..."
# in a layer folder names its own folder or a layer below it, reconstruct/ depends only
# on core/, and inside scene/ the model (everything but scene/loaders/) never includes
# the loaders. Prints each offending line as file:line: problem and fails on any.
# Usage: check_layers.sh [REPO_ROOT]
set -u
cd "${1:-$(dirname "$0")/../..}" || exit 2
# Bottom to top. A layer may include any layer of a lower rank (reconstruct: core only).
ranks=(core scene reconstruct pathspace manifold gradients kernels_adaptive mcmc
       integrators experiments apps)
rank_of() { local i; for i in "${!ranks[@]}"; do [ "${ranks[$i]}" = "$1" ] && echo "$i" && return; done; echo -1; }
bad=0
report() { echo "$1: $2"; bad=$((bad + 1)); }
for layer in "${ranks[@]}"; do
  [ -d "$layer" ] || { report "$layer" "layer folder missing"; continue; }
  own=$(rank_of "$layer")
  while IFS= read -r hit; do
    file=${hit%%:*}; rest=${hit#*:}; line=${rest%%:*}; text=${rest#*:}
    target=$(sed -E 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"([a-z_]+)\/.*/\1/' <<<"$text")
    [ "$target" = "$text" ] && continue  # not a "<folder>/..." include
    dep=$(rank_of "$target")
    [ "$dep" -lt 0 ] && continue         # not a layer (e.g. a third-party folder)
    if [ "$layer" = reconstruct ] && [ "$target" != core ] && [ "$target" != reconstruct ]; then
      report "$file:$line" "reconstruct/ may include only core/ ($text)"
    elif [ "$target" = reconstruct ] && [ "$own" -le "$(rank_of reconstruct)" ] && [ "$layer" != reconstruct ]; then
      report "$file:$line" "$layer/ is below reconstruct/ ($text)"
    elif [ "$dep" -gt "$own" ]; then
      report "$file:$line" "$layer/ includes the layer above it, $target/ ($text)"
    fi
    if [ "$layer" = scene ] && [[ "$file" != scene/loaders/* ]] && [[ "$text" == *'"scene/loaders/'* ]]; then
      report "$file:$line" "the scene model includes a loader ($text)"
    fi
  done < <(grep -rnE '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' "$layer" --include='*.h' --include='*.cpp')
done
if [ "$bad" -gt 0 ]; then echo "$bad include(s) against the layer direction"; exit 1; fi
echo "layers: every include points down"
