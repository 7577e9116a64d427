#include <cstdio>
int main() { std::puts("drape"); return 0; }
