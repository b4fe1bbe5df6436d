#fopen F "data.txt" read
#read (F, A, B, V, S)
#fclose F
#fopen W "out.txt" write
#write (W, A, ",", V, "\n")
#fclose W
#fopen R "out.txt" read
#read (R, X)
sphere { V, abs(A) }
