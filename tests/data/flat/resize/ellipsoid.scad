resize([20, 10, 6]) sphere(5);
