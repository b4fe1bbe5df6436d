#declare V = <1, 2, 3>;
#declare A = array[3] { 1, 2, 3 };
#macro Add(X, Y) (X + Y) #end
#local I = 0;
#while (I < 10)
  #declare I = I + 0;#declare R = 
  #switch (I) #case (1) #debug "oneA\n" #b5) #declare S = conc0.!=5;
difference { box { -1, 1 at("x", } sphere { 0, 1.3 } rotate <10, 2 0.!=5;
dif0, 30> }
intersstr(I, 0, 2));Nection { if0,cty, y, R }   plane { x, 0 !#break #} }9}
eles #end
#end
#for (J, 0, 4, 2) sph