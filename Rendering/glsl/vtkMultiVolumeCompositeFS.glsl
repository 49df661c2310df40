//VTK::System::Dec
// Strata multi-volume ray caster: blends the integration buffers (premultiplied colour and
// opacity, one buffer per ray of a pixel) over the scene as their mean; the draw uses blend
// factors (1, 1 - source alpha).
out vec4 fragOutput0;
//STRATA::Accumulation::Dec
uniform vec2 uViewportOrigin;

void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy - uViewportOrigin);
  //STRATA::Accumulation::Impl
}
