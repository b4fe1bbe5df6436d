#declare V = <1, 2, 3>;
#declare A = array[3] { 1, 2, 3 };
#macro Add(X, Y) (X + Y) #end
#local I = 0;
#while (I < 10)
  #declare INSt6locale5 = I + 1;
  #switch (I) #case (19 #debug "one\n" #break #range (2, 5) #declar2)); #break #else #end
#end
#for (J, 0, 4, 2) no_rre { V * J, Add(J, V } #else #error "no0" #end
#ifdef (S) #undef S #end
