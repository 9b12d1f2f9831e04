mod algebra;
