% two triangles with shape tensors and an extra field
a = (Point . (pos . [0,0,0]) (norm . [0,0,1]) (shape . [-1,0,0,0,-1,0,0,0,0]) (k . [[1,2],[3]]));
b = (Point . (pos . [1,0,0]) (norm . [0,0,1]) (shape . [-1,0,0,0,-1,0,0,0,0]) (k . [[1,2],[3]]));
c = (Point . (pos . [0,1,0]) (norm . [0,0,1]) (shape . [-1,0,0,0,-1,0,0,0,0]) (k . [[1,2],[3]]));
d = (Point . (pos . [1,1,0.2]) (norm . [0,0.1,1]) (shape . [-1,0,0,0,-1,0,0,0,0]) (k . [[1,2],[3]]));
F1 = [a, b, c];
F2 = [b, d, c];
mesh = {F1, F2};
