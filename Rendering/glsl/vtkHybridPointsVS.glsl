//VTK::System::Dec
// Strata hybrid point + volume renderer (Wilson, Ma and McCormick, "A hybrid point and volume
// rendering"): one point where the low-resolution volume is wrong, drawn as a screen-aligned
// square or a Gaussian splat the size of its error-grid cell on screen. A point stands for a
// cell of side g in which the original value s replaces the low-resolution value r = s - e that
// the volume pass already composited there; drawn in front of that, it carries exactly the
// missing part: opacity (A_s - A_r) / (1 - A_r) and colour C_s - (1 - a) C_r, with A and C the
// opacity and premultiplied colour of a cell-thick layer of each value. Footprints are rounded
// up to whole pixels with opacity reduced by the area ratio (the paper's rounding), so what a
// point adds to the image does not depend on the rounding.
in vec3 vertexLocal;
in float pointValue;
in float pointError;
//STRATA::Normal::Dec
uniform mat4 uLocalToClip;
uniform float uCellSize;      // g, world units
uniform float uPixelsPerUnit; // pixels per world unit at w = 1
uniform sampler2D uTransfer;  // rgb, extinction per unit length
uniform vec3 uTableRange;     // (s - x) * y + z: table coordinate
out vec4 vColor;              // premultiplied, footprint-corrected
//STRATA::Splat::VSDec

// Colour and opacity of a cell-thick layer of value s.
vec4 strataLayer(float s)
{
  vec4 tf = texture(uTransfer, vec2((s - uTableRange.x) * uTableRange.y + uTableRange.z, 0.5));
  float a = 1.0 - exp(-tf.a * uCellSize);
  return vec4(tf.rgb * a, a);
}

void main()
{
  vec4 p = uLocalToClip * vec4(vertexLocal, 1.0);
  vec4 S = strataLayer(pointValue);
  vec4 R = strataLayer(pointValue - pointError);
  float a = R.a < 1.0 ? max(S.a - R.a, 0.0) / (1.0 - R.a) : 0.0;
  vec3 c = max(S.rgb - (1.0 - a) * R.rgb, vec3(0.0));
  //STRATA::Normal::Impl
  float size = uCellSize * uPixelsPerUnit / max(p.w, 1.0e-30);
  if (a <= 0.0 || p.w <= 0.0)
  {
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0); // nothing to add: outside the clip volume
    gl_PointSize = 1.0;
    vColor = vec4(0.0);
    //STRATA::Splat::VSCulled
    return;
  }
  gl_Position = p;
  //STRATA::Splat::VSImpl
}
