# Sourced by tools/setup.sh and tools/debian13.sh: the Debian archive URI of
# this system's own apt source for a suite (deb822 .sources files and
# one-line .list files both count), so that nothing names a mirror itself.
#   debian_uri CODENAME   prints the URI, or fails when there is none
debian_uri() {
  local codename=$1 f
  for f in /etc/apt/sources.list.d/*.sources; do
    [ -f "$f" ] || continue
    awk -v c="$codename" '
      /^[[:space:]]*$/ { if (uri && suite) { print uri; exit } uri=""; suite="" ; next }
      tolower($1)=="uris:" { for (i=2;i<=NF;i++) if ($i ~ /debian\/?$/) uri=$i }
      tolower($1)=="suites:" { for (i=2;i<=NF;i++) if ($i==c) suite=1 }
      END { if (uri && suite) print uri }' "$f" | head -n1
  done | head -n1 | grep . && return 0
  cat /etc/apt/sources.list /etc/apt/sources.list.d/*.list 2>/dev/null |
    awk -v c="$codename" '$1=="deb" { for (i=2;i<=NF;i++) if ($i ~ /^[a-z]+:/ && $(i+1)==c && $i ~ /debian\/?$/) { print $i; exit } }' |
    head -n1 | grep .
}
