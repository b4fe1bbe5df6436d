#declare V = <1, 2, 3>;
#declare A = array[3] { 1, 2, 3 };
#macro Add(X, Y) (X + Y) #end
#local I = 0;
#while (I < 10)
  #declare I = I + 1;
  #switch (I) #case (1) #debug "one\n" #break #range (2, 5) #declare S = concat("x", str(I, 0, 2)); #break #else #end
#end
#for (J, 0, 4, 2) sphere { V * J, Add(J, 1) / 10 } #end
#if (vlength(V) > 3 & A[1] = 2) box { -V, V } #else #error "no" #end
#ifdef (S) #undef S #end
