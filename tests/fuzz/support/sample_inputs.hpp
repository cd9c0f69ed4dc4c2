#pragma once
// Tiny hand-written data sets for the targets that need a store or a network behind them
// (the request handlers, the WebSocket endpoints): a 5-station metro in LOOM GeoJSON, a few
// POIs as CSV around it, and a 3 x 3 street grid as OSM XML. Coordinates are in Vienna.

namespace tourmap::fuzz {

inline constexpr const char* kLoomMetro = R"({"type":"FeatureCollection","features":[
{"type":"Feature","geometry":{"type":"Point","coordinates":[16.360,48.200]},"properties":{"id":"a","station_id":"A","station_label":"Alpha"}},
{"type":"Feature","geometry":{"type":"Point","coordinates":[16.370,48.210]},"properties":{"id":"b","station_id":"B","station_label":"Bravo"}},
{"type":"Feature","geometry":{"type":"Point","coordinates":[16.380,48.200]},"properties":{"id":"c","station_id":"C","station_label":"Charlie"}},
{"type":"Feature","geometry":{"type":"Point","coordinates":[16.370,48.190]},"properties":{"id":"d","station_id":"D","station_label":"Delta"}},
{"type":"Feature","geometry":{"type":"Point","coordinates":[16.390,48.212]},"properties":{"id":"e","station_id":"E","station_label":"Echo"}},
{"type":"Feature","geometry":{"type":"LineString","coordinates":[[16.360,48.200],[16.365,48.206],[16.370,48.210]]},"properties":{"from":"a","to":"b","lines":[{"id":"u1","label":"U1","color":"e3000f"}]}},
{"type":"Feature","geometry":{"type":"LineString","coordinates":[[16.370,48.210],[16.390,48.212]]},"properties":{"from":"b","to":"e","lines":[{"id":"u1","label":"U1","color":"e3000f"}]}},
{"type":"Feature","geometry":{"type":"LineString","coordinates":[[16.360,48.200],[16.370,48.190]]},"properties":{"from":"a","to":"d","lines":[{"id":"u2","label":"U2","color":"a862a4"}]}},
{"type":"Feature","geometry":{"type":"LineString","coordinates":[[16.370,48.190],[16.380,48.200]]},"properties":{"from":"d","to":"c","lines":[{"id":"u2","label":"U2","color":"a862a4"}]}},
{"type":"Feature","geometry":{"type":"LineString","coordinates":[[16.370,48.210],[16.380,48.200]]},"properties":{"from":"b","to":"c","lines":[{"id":"u3","label":"U3","color":"ef7c00"},{"id":"u2","label":"U2","color":"a862a4"}]}}
]})";

inline constexpr const char* kPoiCsv =
    "name,lon,lat,category,rank,url\n"
    "Opera,16.369,48.203,sight,1,https://example.org/opera\n"
    "Museum,16.361,48.204,museum,2,\n"
    "Park,16.381,48.205,park,NULL,\n"
    "Church,16.372,48.208,sight,3,\"https://a.example, https://b.example\"\n"
    "Market,16.366,48.195,market,,\n"
    "Tower,16.388,48.211,sight,5,\n";

inline constexpr const char* kOsmGrid = R"(<?xml version="1.0" encoding="UTF-8"?>
<osm version="0.6" generator="hand">
 <node id="1" lat="48.200" lon="16.360" version="1"/>
 <node id="2" lat="48.200" lon="16.365" version="1"/>
 <node id="3" lat="48.200" lon="16.370" version="1"/>
 <node id="4" lat="48.205" lon="16.360" version="1"/>
 <node id="5" lat="48.205" lon="16.365" version="1"/>
 <node id="6" lat="48.205" lon="16.370" version="1"/>
 <node id="7" lat="48.210" lon="16.360" version="1"/>
 <node id="8" lat="48.210" lon="16.365" version="1"/>
 <node id="9" lat="48.210" lon="16.370" version="1"/>
 <way id="101" version="1"><nd ref="1"/><nd ref="2"/><nd ref="3"/><tag k="highway" v="primary"/><tag k="name" v="South"/></way>
 <way id="102" version="1"><nd ref="4"/><nd ref="5"/><nd ref="6"/><tag k="highway" v="residential"/></way>
 <way id="103" version="1"><nd ref="7"/><nd ref="8"/><nd ref="9"/><tag k="highway" v="secondary"/><tag k="name" v="North"/></way>
 <way id="104" version="1"><nd ref="1"/><nd ref="4"/><nd ref="7"/><tag k="highway" v="tertiary"/></way>
 <way id="105" version="1"><nd ref="2"/><nd ref="5"/><nd ref="8"/><tag k="highway" v="footway"/></way>
 <way id="106" version="1"><nd ref="3"/><nd ref="6"/><nd ref="9"/><tag k="highway" v="service"/></way>
</osm>
)";

}  // namespace tourmap::fuzz
