// A triangle that covers the viewport, from gl_VertexID alone (no vertex buffer): vertices
// (-1,-1), (3,-1), (-1,3) in clip space. Depth is the far plane of reversed-Z (0).
out vec2 screen_uv;  // [0, 1]^2 over the viewport, v = 0 at the bottom row

void main() {
  const vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  screen_uv = corner;
  gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
