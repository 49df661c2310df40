//VTK::System::Dec
// Strata multi-volume ray caster: blends the integration buffer (premultiplied colour and
// opacity of every ray) over the scene; the draw uses blend factors (1, 1 - source alpha).
out vec4 fragOutput0;
uniform sampler2D uAccumulation;
uniform vec2 uViewportOrigin;

void main()
{
  fragOutput0 = texelFetch(uAccumulation, ivec2(gl_FragCoord.xy - uViewportOrigin), 0);
}
