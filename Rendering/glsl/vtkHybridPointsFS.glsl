//VTK::System::Dec
// Strata hybrid point + volume renderer: one fragment of a point's footprint, premultiplied,
// blended with factors (1, 1 - source alpha) over the slabs of the volume behind it.
//VTK::Output::Dec
in vec4 vColor;
//STRATA::Splat::FSDec

void main()
{
  //STRATA::Splat::FSImpl
}
