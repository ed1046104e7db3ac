"""`morsec run --foxglove`: the running simulation on Foxglove's WebSocket protocol (the foxglove-sdk
package, imported only when asked for): `world` (MuJoCo's bodies as a transform tree and its geoms as a 3D
scene), `streams` (each component's messages as a Foxglove channel), `server` (the server, fed by the loop).
docs/foxglove.md says what a user sees and why this is a run option rather than a middleware."""
