# Sourced by the bench scripts (sweep_families.sh, performance.sh): a scene
# file edited key by key, so that a benchmark runs a shipped case with other
# numerics without a copy of it in the repository.

# scene_edit IN OUT SECTION KEY VALUE|--delete [SECTION KEY VALUE ...]: a copy with keys
# replaced (or deleted); fails if a key to replace is not in its section
scene_edit() {
  local in=$1 out=$2; shift 2
  local spec=""
  while (($#)); do spec+="$1"$'\x1f'"$2"$'\x1f'"$3"$'\x1e'; shift 3; done
  awk -v spec="$spec" '
    BEGIN { n = split(spec, e, "\036"); m = 0
            for (i = 1; i <= n; i++) if (e[i] != "") { split(e[i], f, "\037"); m++; S[m] = f[1]; K[m] = f[2]; V[m] = f[3]; hit[m] = 0 } }
    { line = $0; sub(/\r$/, "", line) }
    line ~ /^[[:space:]]*\[/ { s = line; gsub(/[][[:space:]]/, "", s); cur = s; print line; next }
    {
      k = line; sub(/=.*/, "", k); gsub(/[[:space:]]/, "", k)
      for (j = 1; j <= m; j++)
        if (cur == S[j] && k == K[j] && index(line, "=") > 0 && line !~ /^[[:space:]]*[;#]/) {
          hit[j] = 1
          if (V[j] != "--delete") print K[j] " = " V[j]
          next
        }
      print line
    }
    END { bad = 0; for (j = 1; j <= m; j++) if (!hit[j] && V[j] != "--delete") { print "missing [" S[j] "] " K[j] > "/dev/stderr"; bad = 1 }; exit bad }
  ' "$in" >"$out"
}
