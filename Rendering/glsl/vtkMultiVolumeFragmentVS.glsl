//VTK::System::Dec
// Strata multi-volume ray caster: the faces of one convex BSP fragment, in the local frame (world
// minus a double-precision origin near the data, so UTM-scale scenes keep their precision).
// With several rays per pixel the outline is pushed out by uDilate pixels from the fragment's
// centre, so that pixels whose centre lies just outside still cast their sub-pixel rays (the
// fragment shader clips every ray to the fragment's planes exactly).
in vec3 vertexLocal;
uniform mat4 uLocalToClip;
uniform vec3 uCentroid;
uniform float uDilate;
uniform vec2 uViewportSize;

void main()
{
  vec4 p = uLocalToClip * vec4(vertexLocal, 1.0);
  vec4 c = uLocalToClip * vec4(uCentroid, 1.0);
  if (uDilate > 0.0 && p.w > 0.0 && c.w > 0.0)
  {
    vec2 away = (p.xy / p.w - c.xy / c.w) * uViewportSize;
    float len = length(away);
    if (len > 0.0)
    {
      p.xy += away / len * (2.0 * uDilate) / uViewportSize * p.w;
    }
  }
  gl_Position = p;
}
