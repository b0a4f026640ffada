// a public header named like a cmd file
