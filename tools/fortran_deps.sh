#!/bin/sh
# Emit make rules "OBJ: OBJS-OF-USED-MODULES" for free-form Fortran sources,
# and "OBJ: FILE" for each file a source includes (include 'FILE', found in
# the source's directory).
# usage: fortran_deps.sh OBJDIR file.f90 ...
# Only modules defined in the given files produce dependencies; intrinsic and
# external modules (iso_fortran_env, iso_c_binding, ...) are ignored.
objdir=$1; shift
awk -v objdir="$objdir" '
function objname(f,   b) { b = f; sub(/.*\//, "", b); sub(/\.f90$/, ".o", b); return objdir "/" b }
FNR == 1 { files[++nf] = FILENAME }
{
  line = tolower($0); sub(/!.*/, "", line)
  if (match(line, /^[ \t]*module[ \t]+[a-z0-9_]+[ \t]*$/)) {
    split(line, w, /[ \t]+/); name = (w[1] == "" ? w[3] : w[2])
    if (name != "procedure") defines[name] = FILENAME
  }
  if (match(line, /^[ \t]*use[ \t,]+/)) {
    s = line; sub(/^[ \t]*use[ \t]*(,[ \t]*(non_)?intrinsic[ \t]*::)?[ \t]*(::)?[ \t]*/, "", s)
    sub(/[ \t,].*/, "", s)
    if (s != "") uses[FILENAME, s] = 1
  }
  if (match(line, /^[ \t]*include[ \t]*[^a-z0-9_ \t]/)) {
    s = $0; sub(/^[ \t]*[iI][nN][cC][lL][uU][dD][eE][ \t]*/, "", s)
    q = substr(s, 1, 1); s = substr(s, 2); s = substr(s, 1, index(s, q) - 1)
    d = FILENAME; if (!sub(/\/[^\/]*$/, "", d)) d = "."
    includes[FILENAME, d "/" s] = 1
  }
}
END {
  for (k in uses) {
    split(k, p, SUBSEP); f = p[1]; m = p[2]
    if ((m in defines) && defines[m] != f) print objname(f) ": " objname(defines[m])
  }
  for (k in includes) {
    split(k, p, SUBSEP); print objname(p[1]) ": " p[2]
  }
}' "$@" | sort -u
