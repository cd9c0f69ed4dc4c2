-- tourmap store, version 4: line styles. Lines whose colours are too close on one map get a
-- distinct stroke style at import (core/metro/line_styles.hpp), stored as JSON
-- ({"casing": true} or {"dash": [2, 1]}); '' is a plain stroke. Metro imports made before
-- this version have a different fingerprint (store/importer.hpp: kMetroProcessing), so the
-- next import of the same files fills it in.
ALTER TABLE metro_lines ADD COLUMN style TEXT NOT NULL DEFAULT '';
