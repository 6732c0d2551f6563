#include <cstdio>
int main() { std::fputs("liftremesh: the pipeline is not built yet\n", stderr); return 2; }
