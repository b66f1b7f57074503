#!/usr/bin/env bash
# Builds the docs site from docs/ into out/site/ (or --out DIR) with mkdocs
# --strict: a broken link, a missing image or a page left out of mkdocs.yml's
# nav fails the build. Prints the index.html to open (from disk or a server).
#   tools/site.sh [--out DIR]
#   tools/site.sh --repo-url   (prints the repository link it would give, or nothing)
set -euo pipefail
cd "$(dirname "$0")/.."
out=out/site; repo_url_only=0
while [ $# -gt 0 ]; do
  case "$1" in
    --out) out="$2"; shift ;;
    --repo-url) repo_url_only=1 ;;
    *) echo "site.sh: unknown argument $1 (usage: tools/site.sh [--out DIR | --repo-url])" >&2; exit 2 ;;
  esac
  shift
done
# The repository link and each page's edit link, only for a clone of a
# public repository: its origin's web address (https, or git@host:path as
# https), never a made-up one. GitHub and GitLab get an edit link too.
remote=$(git remote get-url origin 2>/dev/null || true)
case "$remote" in
  git@*:*) hostpath=${remote#git@}; remote="https://${hostpath%%:*}/${hostpath#*:}" ;;
  ssh://*) hostpath=${remote#ssh://}; remote="https://${hostpath#*@}" ;;
esac
case "$remote" in
  https://*) rest=${remote#https://}; host=${rest%%/*}  # no user or token in a link
             remote="https://${host##*@}${rest#"$host"}"; remote=${remote%/}; remote=${remote%.git} ;;
  *) remote="" ;;
esac
if [ $repo_url_only -eq 1 ]; then
  [ -z "$remote" ] || echo "$remote"
  exit 0
fi
if ! command -v mkdocs >/dev/null; then
  echo "site.sh: mkdocs is not installed (Debian: mkdocs mkdocs-material python3-pymdownx libjs-katex; tools/setup.sh installs them)" >&2
  exit 1
fi
python3 tools/docs.py --check >&2 || { echo "site.sh: the code quoted in docs/ is stale" >&2; exit 1; }
log=$(mktemp); config=mkdocs.yml
trap 'rm -f "$log"; [ "$config" = mkdocs.yml ] || rm -f "$config"' EXIT
if [ -n "$remote" ]; then
  branch=$(git rev-parse --abbrev-ref HEAD 2>/dev/null || true)
  # mkdocs reads paths relative to its config file: this one lies beside mkdocs.yml
  config=$(mktemp -p . .mkdocs-site-XXXXXX.yml)
  { echo "INHERIT: mkdocs.yml"; echo "repo_url: $remote"
    case "$branch:$remote" in
      HEAD:* | :*) echo "edit_uri: ''" ;;  # no branch to edit on
      *:https://github.com/*) echo "edit_uri: edit/$branch/docs/" ;;
      *:https://gitlab.com/*) echo "edit_uri: -/edit/$branch/docs/" ;;
      *) echo "edit_uri: ''" ;;
    esac; } > "$config"
fi
# mkdocs (Debian's, /usr/bin/mkdocs) runs on the system's Python 3.
if ! mkdocs build --strict --clean -f "$config" --site-dir "$out" >"$log" 2>&1; then
  grep -E "WARNING|ERROR|Error|Aborted" "$log" >&2 || cat "$log" >&2
  echo "site.sh: the site did not build" >&2
  exit 1
fi
echo "site: $(cd "$out" && pwd)/index.html"
