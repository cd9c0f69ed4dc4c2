#!/bin/sh
# Imports the mounted sample data (unchanged files are skipped), then serves.
set -e
mkdir -p "$(dirname "$TOURMAP_DB")"
if [ -d "$TOURMAP_DATA_DIR" ]; then
  tourmap import manifest /usr/share/tourmap/sample-data.json --data-dir "$TOURMAP_DATA_DIR" --db "$TOURMAP_DB"
else
  echo "no data mounted at $TOURMAP_DATA_DIR; serving what the database holds" >&2
  tourmap migrate --db "$TOURMAP_DB"
fi
exec tourmap serve "$@"
