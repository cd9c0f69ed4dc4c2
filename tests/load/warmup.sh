# shellcheck shell=bash disable=SC2154  # port and log come from the caller
# tm_warm_up: computes once what the load scripts hit (city reads, metro layouts, cluster trees in
# both spaces, road bbox reads) and exports the boxes the wrk scripts draw windows from:
#   CITIES (id=POI or city bbox), ROADS (id=bbox), GEO (cities with POIs: id=POI bbox),
#   LAYOUT (cities with POIs: id=extent of the POIs in layout space).
# Sourced after lib.sh by tests/load/run.sh and tests/load/soak.sh; needs a running server.
tm_warm_up() {
  local cities roads entry city layout box
  cities="$(tm_get /api/v1/cities)"
  roads="$(tm_get /api/v1/roads)"
  export CITIES ROADS GEO LAYOUT
  CITIES="$(tm_json '" ".join(c["id"] + "=" + ",".join(map(str, c.get("poi_bbox") or c["bbox"])) for c in d["cities"])' <<<"$cities")"
  ROADS="$(tm_json '" ".join(r["id"] + "=" + ",".join(map(str, r["bbox"])) for r in d["roads"])' <<<"$roads")"
  GEO="$(tm_json '" ".join(c["id"] + "=" + ",".join(map(str, c["poi_bbox"])) for c in d["cities"] if c["counts"]["pois"])' <<<"$cities")"
  LAYOUT=
  for entry in $CITIES; do
    city="${entry%%=*}"
    log "warm-up: $city (city, metro, POIs, layout)"
    tm_get "/api/v1/cities/$city" >/dev/null
    tm_get "/api/v1/cities/$city/metro" >/dev/null
    tm_get "/api/v1/cities/$city/pois" >/dev/null
    layout="$(tm_get "/api/v1/cities/$city/layout")"
    if [[ " $GEO " == *" $city="* ]]; then  # POIs: cluster trees in both spaces, layout-space extent
      box="$(tm_json '",".join(str(f([p["geometry"]["coordinates"][i] for p in d["pois"]["features"]])) for f, i in ((min, 0), (min, 1), (max, 0), (max, 1)))' <<<"$layout")"
      LAYOUT="${LAYOUT:+$LAYOUT }$city=$box"
      tm_get "/api/v1/cities/$city/clusters?m=10" >/dev/null
      tm_get "/api/v1/cities/$city/clusters?m=10&space=layout&bbox=$box" >/dev/null
    fi
  done
  for entry in $ROADS; do tm_get "/api/v1/roads/${entry%%=*}?bbox=${entry#*=}" >/dev/null; done
}

# tm_deform_boxes IDS: "id=bbox ..." for the named road networks (from ROADS), after warming each
# one's grid and factorization with one focus request. Fails for an unknown id.
tm_deform_boxes() {
  local id box out=
  for id in "$@"; do
    box="$(tr ' ' '\n' <<<"$ROADS" | sed -n "s/^$id=//p")"
    [[ -n "$box" ]] || { echo "no road network $id" >&2; return 2; }
    out="${out:+$out }$id=$box"
    log "warm-up: deform focus on $id (grid and factorization)"
    curl -sf -o /dev/null "http://127.0.0.1:$port/api/v1/deform/focus" -H 'Content-Type: application/json' \
      -d "{\"roads\":\"$id\",\"regions\":[{\"center\":[$(cut -d, -f1 <<<"$box"),$(cut -d, -f2 <<<"$box")],\"radius_m\":300,\"scale\":3}],\"output\":{\"roads\":\"none\"}}"
  done
  echo "$out"
}
