#include "strata/gpu/Query.h"

namespace strata::gpu {

Query::Query(std::string_view label, GLenum target) : target_(target) {
    GLuint id = 0;
    glCreateQueries(target, 1, &id);
    name_ = GlName<QueryDeleter>(id);
    setLabel(GL_QUERY, id, label);
}

void Query::begin() { glBeginQuery(target_, id()); }
void Query::end() { glEndQuery(target_); }
void Query::timestamp() { glQueryCounter(id(), GL_TIMESTAMP); }

bool Query::available() const {
    GLint ready = 0;
    glGetQueryObjectiv(id(), GL_QUERY_RESULT_AVAILABLE, &ready);
    return ready != 0;
}

std::uint64_t Query::result() const {
    GLuint64 value = 0;
    glGetQueryObjectui64v(id(), GL_QUERY_RESULT, &value);
    return value;
}

}  // namespace strata::gpu
