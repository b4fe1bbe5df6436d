#declare R = 0.5;
difference { box { -1, 1 } sphere { 0, 1.3 } rotate <10, 20, 30> }
intersection { cylinder { -y, y, R } torus { 1, R } translate x * 3 }
union { cone { 0, 1, y, 0 open } disc { 0, y, 1 } clipped_by { plane { x, 0 } } }
