# Sourced by the *_variant.sh scripts: a fresh copy of the repository's cases/ in $work/cases with
# $work/data linked to its data/ (studies name their curves as ../data/...), and $work/out removed.
# Needs $work set; sets $repo.
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)
rm -rf "$work/cases" "$work/data" "$work/out"
mkdir -p "$work"
cp -r "$repo/cases" "$work/cases"
ln -s "$repo/data" "$work/data"
