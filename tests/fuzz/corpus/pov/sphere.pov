camera { location <0, 1, -5> look_at 0 angle 40 }
light_source { <5, 5, -5> color rgb 1 }
sphere { 0, 1 pigment { checker rgb 1, rgb <1, 0, 0> scale 0.25 } finish { diffuse 0.8 } }
plane { y, -1 pigment { color rgb <0.5, 0.6, 0.7> } }
