#macro R() R() #end
R()
